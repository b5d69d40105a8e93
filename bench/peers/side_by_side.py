#!/usr/bin/python3
"""Our code beside LIGGGHTS 3.8 on the physics (issue 31, verification 3): the comparisons of
bench/peers/run_side_by_side.sh and of the suite test reference.liggghts_settle.

  side_by_side.py settle OURS.csv LIGGGHTS.csv N [--table]
      Series CSVs (seed,step,time_s,ke_J,rke_J,coordination), several seeds each. At every output
      and for each quantity (ke_J, coordination) the codes' seed means must differ by at most
      k x the pooled seed standard deviation (plus a floor, below); prints a summary line per
      quantity (with --table, a markdown table of the outputs) and exits 1 where they do not agree;
      N: the number of particles (the floor).
  side_by_side.py heap-angle FILE...
      Final positions (x,y,z,radius a row, whitespace or comma separated, '#' comments): prints
      one repose angle per file (the heap_angle method below).
  side_by_side.py heap ANGLES.csv
      code,seed,angle_deg rows: the two codes' mean angles against k x the pooled seed deviation.
  side_by_side.py settle-plot RUNS.csv OUT.png
      code,seed,step,time_s,ke_J,rke_J,coordination rows: both codes' seed means and ranges over time.
  side_by_side.py heap-plot OUT.png DEM_FILE... -- LIGGGHTS_FILE...
      The surface heights h(r) of heap_angle, every heap of both codes.
  side_by_side.py lammps-log LOG
      LIGGGHTS thermo (step atoms ke c_rke v_zmax c_ncontacts) to step,ke_J,rke_J,coordination.
  side_by_side.py dump-final DUMP
      The last frame of a LIGGGHTS custom dump (id x y z radius) as x,y,z,radius rows.
  side_by_side.py checkpoint-positions FILE.h5
      Our checkpoint's particles as x,y,z,radius rows.

The tolerance: with n1 and n2 seeds, s_p the pooled seed standard deviation, the difference of the
means has standard error s_p sqrt(1/n1 + 1/n2); k = t(n1 + n2 - 2, 1 - alpha / (2 M)) sqrt(1/n1 +
1/n2) (Student's t, Bonferroni over the M comparisons made, alpha = 0.05): codes with the same
physics fail one of the M comparisons by chance less than 5 % of the time (the outputs of a series
are correlated in time, so less still). Where every seed gives the same value (no contact yet), a
floor stands for s_p: one pair contact (2/N) for the coordination, 1e-6 of the largest mean
kinetic energy for the energy.
"""
import math
import sys

import numpy as np
from scipy import stats

ALPHA = 0.05


def tolerance_factor(n1, n2, comparisons, alpha=ALPHA):
    """k of the module docstring: the allowed |mean difference| in units of the pooled deviation."""
    return stats.t.ppf(1 - alpha / (2 * comparisons), n1 + n2 - 2) * math.sqrt(1 / n1 + 1 / n2)


def pooled_sd(a, b):
    """Pooled standard deviation of two samples (rows: seeds), column-wise."""
    n1, n2 = len(a), len(b)
    return np.sqrt(((n1 - 1) * a.var(axis=0, ddof=1) + (n2 - 1) * b.var(axis=0, ddof=1)) / (n1 + n2 - 2))


def read_series(path):
    """{seed: structured rows} of a seed,step,... CSV."""
    data = np.genfromtxt(path, delimiter=",", names=True)
    return {int(s): data[data["seed"] == s] for s in np.unique(data["seed"])}


def stack(series, column, steps):
    """Rows: seeds; columns: the outputs at `steps` (every run must have them all)."""
    rows = []
    for seed, rows_of_seed in sorted(series.items()):
        by_step = dict(zip(rows_of_seed["step"].astype(int), rows_of_seed[column]))
        missing = [s for s in steps if s not in by_step]
        if missing:
            raise SystemExit(f"seed {seed}: no output at steps {missing[:5]}")
        rows.append([by_step[s] for s in steps])
    return np.array(rows)


def compare_settle(ours_path, ref_path, n_particles, table=False):
    ours, ref = read_series(ours_path), read_series(ref_path)
    steps = sorted(set(ref[min(ref)]["step"].astype(int)))
    quantities = ("ke_J", "coordination")
    k = tolerance_factor(len(ours), len(ref), len(steps) * len(quantities))
    agree = True
    lines = []
    for q in quantities:
        a, b = stack(ours, q, steps), stack(ref, q, steps)
        ma, mb = a.mean(axis=0), b.mean(axis=0)
        sp = pooled_sd(a, b)
        floor = 2.0 / n_particles if q == "coordination" else 1e-6 * max(ma.max(), mb.max())
        allowed = k * np.maximum(sp, floor)
        ratio = np.abs(ma - mb) / allowed
        worst = int(np.argmax(ratio))
        bad = [steps[i] for i in np.nonzero(ratio > 1)[0]]
        agree &= not bad
        print(f"{q}: {len(ours)} seeds ours, {len(ref)} LIGGGHTS, {len(steps)} outputs, k = {k:.3f}; "
              f"largest |difference| / (k s_p) = {ratio[worst]:.3f} at step {steps[worst]} "
              f"(ours {ma[worst]:.6g}, LIGGGHTS {mb[worst]:.6g}, s_p {sp[worst]:.3g}); "
              + ("agree at every output" if not bad else f"DISAGREE at {len(bad)} outputs, from step {bad[0]}"))
        lines.append((q, ma, mb, sp, ratio))
    if table:
        print("\n| step | KE ours (J) | KE LIGGGHTS (J) | s_p | diff/(k s_p) | Z ours | Z LIGGGHTS | s_p | diff/(k s_p) |")
        print("|---|---|---|---|---|---|---|---|---|")
        (_, ka, kb, ks, kr), (_, za, zb, zs, zr) = lines
        for i, s in enumerate(steps):
            print(f"| {s} | {ka[i]:.4e} | {kb[i]:.4e} | {ks[i]:.2e} | {kr[i]:.2f} | {za[i]:.3f} | {zb[i]:.3f} | {zs[i]:.3f} | {zr[i]:.2f} |")
    return agree


def read_positions(path):
    rows = []
    with open(path) as f:
        for line in f:
            line = line.split("#")[0].replace(",", " ").split()
            if len(line) == 4:
                try:
                    rows.append([float(v) for v in line])
                except ValueError:
                    pass  # a header
    return np.array(rows)


def surface(xyza, bin_width=0.002):
    """Ring centres and the highest sphere top (z + a) in each ring of width `bin_width` around
    the pour axis x = y = 0."""
    r = np.hypot(xyza[:, 0], xyza[:, 1])
    ring = (r / bin_width).astype(int)
    h = np.zeros(ring.max() + 1)
    np.maximum.at(h, ring, xyza[:, 2] + xyza[:, 3])
    return (np.arange(len(h)) + 0.5) * bin_width, h


def heap_angle(xyza, bin_width=0.002):
    """Repose angle (degrees) of a heap poured on the axis x = y = 0: the surface height h(r) is
    the highest sphere top (z + a) in rings of width `bin_width` (one diameter) around the axis;
    a straight line is fitted to h(r) over the rings whose h lies between 20 % and 80 % of the
    heap's height (the flank, away from the rounded top and the spread foot); the angle is
    atan(-slope)."""
    centres, h = surface(xyza, bin_width)
    height = h[:2].max()
    # The flank: from the axis outwards, the rings before the surface first drops below 20 %.
    end = int(np.argmax(h < 0.2 * height)) if (h < 0.2 * height).any() else len(h)
    flank = [i for i in range(end) if 0.2 * height <= h[i] <= 0.8 * height]
    if len(flank) < 3:
        raise SystemExit(f"heap: only {len(flank)} rings on the flank")
    slope = np.polyfit(centres[flank], h[flank], 1)[0]
    return math.degrees(math.atan(-slope))


def compare_heap(path):
    data = np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding=None)
    angles = {c: np.array([a for cc, a in zip(data["code"], data["angle_deg"]) if cc == c]) for c in ("dem", "liggghts")}
    a, b = angles["dem"], angles["liggghts"]
    sp = float(pooled_sd(a[:, None], b[:, None])[0])
    k = tolerance_factor(len(a), len(b), 1)
    diff = a.mean() - b.mean()
    ok = abs(diff) <= k * sp
    print(f"repose angle: ours {a.mean():.2f} deg (sd {a.std(ddof=1):.2f}, {len(a)} seeds), LIGGGHTS {b.mean():.2f} deg "
          f"(sd {b.std(ddof=1):.2f}, {len(b)} seeds); difference {diff:+.2f} deg, allowed k s_p = {k:.2f} x {sp:.2f} = "
          f"{k * sp:.2f} deg: " + ("agree" if ok else "DISAGREE"))
    return ok


def settle_plot(runs, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    data = np.genfromtxt(runs, delimiter=",", names=True, dtype=None, encoding=None)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for code, colour in (("dem", "C0"), ("liggghts", "C3")):
        rows = data[data["code"] == code]
        series = {s: rows[rows["seed"] == s] for s in np.unique(rows["seed"])}
        steps = sorted(set(series[min(series)]["step"].astype(int)))
        t = np.array(steps) * (rows["time_s"][1] / rows["step"][1])
        for ax, q in zip(axes, ("ke_J", "coordination")):
            v = stack(series, q, steps)
            ax.plot(t, v.mean(axis=0), color=colour, label=f"{'ours' if code == 'dem' else 'LIGGGHTS 3.8'} ({len(v)} seeds, mean)")
            ax.fill_between(t, v.min(axis=0), v.max(axis=0), color=colour, alpha=0.25, lw=0)
    axes[0].set(xlabel="t (s)", ylabel="translational kinetic energy (J)", yscale="log")
    axes[1].set(xlabel="t (s)", ylabel="mean coordination 2 x pair contacts / N")
    for ax in axes:
        ax.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=90)


def heap_plot(out, dem_files, liggghts_files):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4))
    for files, colour, label in ((dem_files, "C0", "ours"), (liggghts_files, "C3", "LIGGGHTS 3.8")):
        for i, p in enumerate(files):
            c, h = surface(read_positions(p))
            ax.plot(1e3 * c, 1e3 * h, color=colour, alpha=0.7, label=label if i == 0 else None)
    ax.set(xlabel="distance from the pour axis (mm)", ylabel="surface height (mm)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=90)


def lammps_log(path):
    """LIGGGHTS thermo rows (custom step atoms ke c_rke v_zmax c_ncontacts: LIGGGHTS cuts the
    headers to 10 characters, so the columns are read by position) as CSV."""
    print("step,ke_J,rke_J,coordination")
    in_table = False
    with open(path) as f:
        for line in f:
            w = line.split()
            if w[:3] == ["Step", "Atoms", "KinEng"]:
                in_table = True
            elif in_table and len(w) == 6 and w[0].isdigit():
                print(f"{w[0]},{w[2]},{w[3]},{float(w[5]) / float(w[1]):.6f}")
            else:
                in_table = False


def dump_final(path):
    """The last frame of a custom dump (id x y z radius) as x,y,z,radius rows."""
    frames, rows = [], None
    with open(path) as f:
        for line in f:
            if line.startswith("ITEM: ATOMS"):
                rows = []
                frames.append(rows)
            elif line.startswith("ITEM:"):
                rows = None
            elif rows is not None:
                w = line.split()
                rows.append(w[1:5])
    print("x,y,z,radius")
    for w in frames[-1]:
        print(",".join(w))


def checkpoint_positions(path):
    import h5py
    with h5py.File(path, "r") as f:
        rows = np.column_stack([f["particles/position"][:], f["particles/radius"][:]])
    np.savetxt(sys.stdout, rows, delimiter=",", header="x,y,z,radius", comments="")


if __name__ == "__main__":
    cmd = sys.argv[1] if len(sys.argv) > 1 else ""
    if cmd == "settle" and len(sys.argv) in (5, 6):
        sys.exit(0 if compare_settle(sys.argv[2], sys.argv[3], int(sys.argv[4]), "--table" in sys.argv) else 1)
    if cmd == "heap-angle" and len(sys.argv) > 2:
        for p in sys.argv[2:]:
            print(f"{heap_angle(read_positions(p)):.3f}")
        sys.exit(0)
    if cmd == "heap" and len(sys.argv) == 3:
        sys.exit(0 if compare_heap(sys.argv[2]) else 1)
    if cmd == "settle-plot" and len(sys.argv) == 4:
        sys.exit(settle_plot(sys.argv[2], sys.argv[3]))
    if cmd == "heap-plot" and "--" in sys.argv:
        cut = sys.argv.index("--")
        sys.exit(heap_plot(sys.argv[2], sys.argv[3:cut], sys.argv[cut + 1:]))
    if cmd == "lammps-log" and len(sys.argv) == 3:
        sys.exit(lammps_log(sys.argv[2]))
    if cmd == "checkpoint-positions" and len(sys.argv) == 3:
        sys.exit(checkpoint_positions(sys.argv[2]))
    if cmd == "dump-final" and len(sys.argv) == 3:
        sys.exit(dump_final(sys.argv[2]))
    sys.exit(__doc__)
