#!/usr/bin/env python3
"""The stress, damage and displacement around a well drilled in a confined slab (thesis §4.4,
workflows/sand-production), against Kirsch's elastic solution (docs/physics.md eq. P80-P83).

Reads post-macro's per-particle output of the drilled state (--vtk, made with --reference: the
Love-Weber stress and the displacement from the state before drilling), the checkpoint holding the
bonds as they were made (Phi = 1 on the contacts of the loaded slab) and the checkpoint after
drilling (or production), and writes, under PREFIX:
  PREFIX_kirsch.csv/.png        sigma_rr and sigma_tt averaged over angle in radial bins (compression
                                positive), Kirsch's values averaged over the same bins, the
                                tolerance of each bin and whether it holds (r >= 2a);
  PREFIX_bonds.csv/.png         the fraction of the bonds in each bin that broke;
  PREFIX_displacement.csv/.png  the mean radial displacement of the particles in each bin
                                (negative: towards the well).
A bin's stress is the box average of post-macro (docs/post.md, "Box averages"): the sum of
V_p sigma_p over the particles whose centre lies in the annulus, over the annulus's volume
(its area times the slab's thickness), each particle's tensor turned into polar components at its
own angle. Exit status 1 if a bin at r >= 2a misses Kirsch by more than its tolerance (with
--check), so that a workflow or a test can fail on it.
"""
import argparse
import math
import sys

from debian_python import ensure  # noqa: E402

ensure("h5py", "numpy", "matplotlib", "vtk")

import h5py  # noqa: E402
import numpy as np  # noqa: E402
import vtk  # noqa: E402
from vtk.util.numpy_support import vtk_to_numpy  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from post_table import save_atomically, write_csv  # noqa: E402


def read_particles(path):
    """Centres, radii, ids, stress tensors (3x3, force index first) and displacements of a
    post-macro .vtu (one vertex per particle)."""
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    out = r.GetOutput()
    pd = out.GetPointData()
    if out.GetNumberOfPoints() == 0 or pd.GetArray("stress") is None:
        sys.exit(f"{path}: no particles with a 'stress' array (post-macro --vtk)")
    if pd.GetArray("displacement") is None:
        sys.exit(f"{path}: no 'displacement' array (post-macro --vtk with --reference)")
    x = vtk_to_numpy(out.GetPoints().GetData()).astype(float)
    a = vtk_to_numpy(pd.GetArray("radius")).astype(float)
    ids = vtk_to_numpy(pd.GetArray("id")).astype(np.int64)
    s = vtk_to_numpy(pd.GetArray("stress")).astype(float).reshape(-1, 3, 3)
    u = vtk_to_numpy(pd.GetArray("displacement")).astype(float)
    return x, a, ids, s, u


def bonded_pairs(path):
    """The (id, id) pairs of a checkpoint's intact bonds (contacts/pair_bonded == 1)."""
    with h5py.File(path, "r") as f:
        ids = f["contacts/pair_ids"][:]
        bonded = f["contacts/pair_bonded"][:]
        pid = f["particles/id"][:]
        x = f["particles/position"][:]
    return ids[bonded == 1], dict(zip(pid.tolist(), range(len(pid)))), x


def kirsch_bin(r1, r2, a):
    """The mean of a^2/r^2 over the annulus r1 < r < r2 (area weight): 2 a^2 ln(r2/r1)/(r2^2 - r1^2)."""
    return 2 * a * a * math.log(r2 / r1) / (r2 * r2 - r1 * r1)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--stress", required=True, help="post-macro --vtk of the drilled state, with --reference")
    ap.add_argument("--bonds-made", required=True, help="checkpoint holding the bonds as made")
    ap.add_argument("--bonds-now", required=True, help="checkpoint after drilling or production")
    ap.add_argument("--centre", required=True, help="the well's axis: x,y (along z)")
    ap.add_argument("--radius", type=float, required=True, help="the well's radius a [m]")
    ap.add_argument("--sigma0", type=float, required=True, help="the far-field stress (compression) [Pa]")
    ap.add_argument("--outer", type=float, required=True, help="the largest radius binned [m] (inside the servo box)")
    ap.add_argument("--bin", type=float, required=True, help="bin width [m] (at least a largest grain)")
    ap.add_argument("--prefix", required=True, help="output path prefix")
    ap.add_argument("--check", action="store_true", help="exit 1 if a bin at r >= 2a misses Kirsch")
    o = ap.parse_args()
    cx, cy = (float(v) for v in o.centre.split(","))
    a, s0 = o.radius, o.sigma0

    x, rad, ids, s, u = read_particles(o.stress)
    dx, dy = x[:, 0] - cx, x[:, 1] - cy
    r = np.hypot(dx, dy)
    c, sn = dx / np.maximum(r, 1e-300), dy / np.maximum(r, 1e-300)
    vol = 4.0 / 3.0 * math.pi * rad ** 3
    sym = 0.5 * (s + np.transpose(s, (0, 2, 1)))
    # Polar components at each particle's angle, compression positive.
    srr = -(c * c * sym[:, 0, 0] + 2 * c * sn * sym[:, 0, 1] + sn * sn * sym[:, 1, 1])
    stt = -(sn * sn * sym[:, 0, 0] - 2 * c * sn * sym[:, 0, 1] + c * c * sym[:, 1, 1])
    ur = c * u[:, 0] + sn * u[:, 1]
    thick = (x[:, 2] + rad).max() - (x[:, 2] - rad).min()
    dmax = 2 * rad.max()

    edges = np.arange(a, o.outer + 1e-12, o.bin)
    rows, bad = [], 0
    for r1, r2 in zip(edges[:-1], edges[1:]):
        m = (r >= r1) & (r < r2)
        n = int(m.sum())
        if n == 0:
            continue
        vbin = math.pi * (r2 * r2 - r1 * r1) * thick
        w = vol[m]
        mrr, mtt = (w * srr[m]).sum() / vbin, (w * stt[m]).sum() / vbin
        # Bin statistics: the bin's value is a sum of n particle terms V_p sigma_p / V_bin, n itself
        # random (how many centres fall in the annulus): its standard error is the root of the sum
        # of the terms' squares (a compound Poisson sum; a dense packing fluctuates less).
        se_rr = math.sqrt(((w * srr[m] / vbin) ** 2).sum())
        se_tt = math.sqrt(((w * stt[m] / vbin) ** 2).sum())
        k = kirsch_bin(r1, r2, a)
        krr, ktt = s0 * (1 - k), s0 * (1 + k)
        # Tolerance (docs/physics.md eq. P83): three standard errors of the bin, plus the finite
        # servo box (Kirsch is for an infinite plate: the hole's image in a box of half-width L
        # changes the stress by about sigma0 a^2/L^2), plus the grain size: a particle counts
        # wholly in the bin of its centre, so a bin reads the field up to a largest grain's radius
        # d_max/2 away, where Kirsch's slope 2 sigma0 a^2/r^3 (largest at r = 2a) changes it by
        # sigma0 d_max/(8a).
        sys_err = s0 * (a * a / (o.outer * o.outer) + dmax / (8 * a))
        tol_rr, tol_tt = 3 * se_rr + sys_err, 3 * se_tt + sys_err
        rc = 0.5 * (r1 + r2)
        checked = r1 >= 2 * a - 1e-12
        ok = (not checked) or (abs(mrr - krr) <= tol_rr and abs(mtt - ktt) <= tol_tt)
        bad += not ok
        rows.append([rc, rc / a, n, mrr, mtt, krr, ktt, tol_rr, tol_tt, int(checked), int(ok), ur[m].mean()])
    if not rows:
        sys.exit(f"{o.stress}: no particle between r = {a} and {o.outer} m")
    write_csv(o.prefix + "_kirsch.csv",
              ["r_m", "r_over_a", "particles", "srr_Pa", "stt_Pa", "kirsch_srr_Pa", "kirsch_stt_Pa",
               "tol_srr_Pa", "tol_stt_Pa", "checked", "within"], [row[:11] for row in rows])
    write_csv(o.prefix + "_displacement.csv", ["r_m", "r_over_a", "particles", "mean_radial_displacement_m"],
              [[row[0], row[1], row[2], row[11]] for row in rows])
    R = np.array([row[0] for row in rows]) / a
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    rr = np.linspace(1, o.outer / a, 200)
    ax.plot(rr, s0 * (1 + rr ** -2) / 1e6, "C0-", label="Kirsch σθθ")
    ax.plot(rr, s0 * (1 - rr ** -2) / 1e6, "C1-", label="Kirsch σrr")
    ax.errorbar(R, [row[4] / 1e6 for row in rows], yerr=[row[8] / 1e6 for row in rows], fmt="C0o", capsize=3, label="σθθ, DEM")
    ax.errorbar(R, [row[3] / 1e6 for row in rows], yerr=[row[7] / 1e6 for row in rows], fmt="C1s", capsize=3, label="σrr, DEM")
    ax.axvline(2, color="0.6", ls=":", label="r = 2a (checked beyond)")
    ax.set_xlabel("r / a")
    ax.set_ylabel("stress, compression positive [MPa]")
    ax.set_title(f"Around the well: a = {a} m, σ0 = {s0 / 1e6:g} MPa")
    ax.legend(fontsize=8)
    save_atomically(fig, o.prefix + "_kirsch.png")
    plt.close(fig)
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    ax.plot(R, [row[11] * 1e3 for row in rows], "C2o-")
    ax.axhline(0, color="0.6", lw=0.8)
    ax.set_xlabel("r / a")
    ax.set_ylabel("mean radial displacement [mm] (negative: towards the well)")
    save_atomically(fig, o.prefix + "_displacement.png")
    plt.close(fig)

    # Broken bonds: the bonds as made whose two particles are both still there, placed at the
    # middle of the pair (as made), against those still intact.
    made, slot0, x0 = bonded_pairs(o.bonds_made)
    now, slot1, _ = bonded_pairs(o.bonds_now)
    intact = set(map(tuple, now.tolist()))
    keep = [(i, j) for i, j in made.tolist() if i in slot1 and j in slot1]
    mid = np.array([0.5 * (x0[slot0[i]] + x0[slot0[j]]) for i, j in keep]).reshape(-1, 3)
    rb = np.hypot(mid[:, 0] - cx, mid[:, 1] - cy)
    broken = np.array([(i, j) not in intact for i, j in keep], dtype=bool)
    brows = []
    for r1, r2 in zip(edges[:-1], edges[1:]):
        m = (rb >= r1) & (rb < r2)
        if m.any():
            brows.append([0.5 * (r1 + r2), 0.5 * (r1 + r2) / a, int(m.sum()), int(broken[m].sum()), broken[m].mean()])
    write_csv(o.prefix + "_bonds.csv", ["r_m", "r_over_a", "bonds", "broken", "broken_fraction"], brows)
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    ax.plot([b[1] for b in brows], [b[4] for b in brows], "C3o-")
    ax.set_xlabel("r / a")
    ax.set_ylabel("broken-bond fraction")
    ax.set_ylim(bottom=0)
    save_atomically(fig, o.prefix + "_bonds.png")
    plt.close(fig)

    peak = max(rows, key=lambda row: row[4])
    print(f"well_report: {len(rows)} bins of {o.bin} m from r = a to {o.outer} m; hoop stress peaks at r/a = {peak[1]:.2f} "
          f"({peak[4] / 1e6:.1f} MPa); {bad} of {sum(row[9] for row in rows)} bins at r >= 2a outside their tolerance; "
          f"{int(broken.sum())} of {len(keep)} bonds broken")
    if o.check and bad:
        sys.exit(1)


if __name__ == "__main__":
    main()
