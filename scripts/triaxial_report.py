#!/usr/bin/env python3
"""Triaxial compression from run-stage's wall log (--wall-forces): the sample between the six faces
of a box wall (BOX.xmin ... BOX.zmax: forces and positions), its deviator stress and volumetric
strain against axial strain (docs/physics.md eq. P66), peak and residual friction angles; for
several runs (fibre contents) the curves together, the strength gain against fibre content with
Michalowski & Zhao's relation (eq. P67-P69), and each segment's fibre tension against its
orientation (the fibre VTK frame nearest the peak).

usage: triaxial_report.py --run LABEL:FIBRE_FRACTION:WALLS.csv[:FIBRES.pvd] ... --summary S.csv
                          --curves C.png [--curves-csv C.csv] [--gain G.png] [--fibres F.png] [--box box]
A fibre fraction is a fraction (0.01 for 1 %). Strains and stresses positive in compression.
"""
import argparse
import csv
import os
import sys
import xml.etree.ElementTree as ET

from debian_python import ensure  # noqa: E402

ensure("numpy", "matplotlib")

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from post_table import save_atomically, write_csv  # noqa: E402

RESIDUAL_SPAN = 0.2  # the residual state: the mean over the last 20 % of the axial strain
# Bands of axial strain over which the summary gives the mean q: two curves compared (a rate check)
# band by band, where the peak alone may sit at different strains on a flat or serrated curve.
BANDS = ((0.0, 0.02), (0.02, 0.05), (0.05, 0.10), (0.10, 0.15))


def read_walls(path: str, box: str):
    """Per logged step: the six faces' forces (what the particles exert) and positions (centres)."""
    rows = {}
    with open(path) as f:
        for r in csv.DictReader(f):
            if not r["wall"].startswith(box + "."):
                continue
            face = r["wall"][len(box) + 1:]
            rows.setdefault(int(r["step"]), {})[face] = (
                float(r["time_s"]), np.array([float(r[k]) for k in ("fx_N", "fy_N", "fz_N")]),
                np.array([float(r[k]) for k in ("cx_m", "cy_m", "cz_m")]))
    faces = [f"{a}{s}" for a in "xyz" for s in ("min", "max")]
    steps = sorted(s for s, v in rows.items() if all(f in v for f in faces))
    if len(steps) < 2:
        sys.exit(f"{path}: fewer than two rows with all six faces of wall '{box}'")
    return [(rows[s]["zmax"][0], {f: rows[s][f][1:] for f in faces}) for s in steps]


def history(path: str, box: str):
    """Eq. P66: sample size from opposite faces, principal stresses from their forces over the
    areas between the other faces, strains from the start of the log."""
    out = {k: [] for k in ("time", "eps_a", "eps_v", "sigma_1", "sigma_3", "q")}
    start = None
    for t, f in read_walls(path, box):
        size = np.array([f[a + "max"][1][k] - f[a + "min"][1][k] for k, a in enumerate("xyz")])
        area = np.array([size[1] * size[2], size[0] * size[2], size[0] * size[1]])
        sigma = np.array([(f[a + "max"][0][k] - f[a + "min"][0][k]) / 2 for k, a in enumerate("xyz")]) / area
        if start is None:
            start = size
        out["time"].append(t)
        out["eps_a"].append(1 - size[2] / start[2])
        out["eps_v"].append(1 - size.prod() / start.prod())
        out["sigma_1"].append(sigma[2])
        out["sigma_3"].append((sigma[0] + sigma[1]) / 2)
        out["q"].append(sigma[2] - (sigma[0] + sigma[1]) / 2)
    return {k: np.array(v) for k, v in out.items()}


def friction_angle(s1, s3):
    """Mobilised friction angle [deg] of a cohesionless material: sin phi = (s1 - s3) / (s1 + s3)."""
    return np.degrees(np.arcsin((s1 - s3) / (s1 + s3)))


def summarise(h):
    k = int(np.argmax(h["q"]))
    tail = h["eps_a"] >= (1 - RESIDUAL_SPAN) * h["eps_a"][-1]
    s1r, s3r = h["sigma_1"][tail].mean(), h["sigma_3"][tail].mean()
    # Dilatancy at the peak: d eps_v / d eps_a by a least-squares line over +-1 % axial strain.
    near = np.abs(h["eps_a"] - h["eps_a"][k]) <= 0.01
    dilatancy = np.polyfit(h["eps_a"][near], h["eps_v"][near], 1)[0] if near.sum() >= 3 else np.nan
    bands = [h["q"][(h["eps_a"] >= lo) & (h["eps_a"] < hi)] for lo, hi in BANDS]
    return dict(q_peak=h["q"][k], eps_peak=h["eps_a"][k], sigma3_peak=h["sigma_3"][k], phi_peak=friction_angle(h["sigma_1"][k], h["sigma_3"][k]),
                q_res=s1r - s3r, phi_res=friction_angle(s1r, s3r), eps_v_end=h["eps_v"][-1], dilatancy_peak=dilatancy,
                q_bands=[b.mean() if b.size else np.nan for b in bands])


def extension_cone(dilatancy):
    """Eq. P67: fibres at an angle theta from the axis with cos^2 theta < c^2 lengthen, where
    c^2 = e3 / (e1 + e3), the lateral strain rate e3 = (1 - d eps_v / d eps_a) e1 / 2."""
    e3 = (1 - dilatancy) / 2
    return np.sqrt(e3 / (1 + e3))


def fibre_factor(c, kp):
    """Eq. P69: Delta q / (rho sigma_f) = K_p (c - c^3/3) / 2 - c^3 / 3 for isotropic fibres."""
    return kp * (c - c ** 3 / 3) / 2 - c ** 3 / 3


def fibre_frame(pvd: str, time: float):
    """The fibre frame nearest `time`: per segment its tension [N], its angle from the axis [deg]
    and its length [m]."""
    ensure("vtk")
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    sets = ET.parse(pvd).getroot().find("Collection").findall("DataSet")
    best = min(sets, key=lambda d: abs(float(d.get("timestep")) - time))
    r = vtkXMLPolyDataReader()
    r.SetFileName(os.path.join(os.path.dirname(pvd), best.get("file")))
    r.Update()
    poly = r.GetOutput()
    pts = vtk_to_numpy(poly.GetPoints().GetData()).reshape(-1, 2, 3)
    span = pts[:, 1] - pts[:, 0]
    length = np.linalg.norm(span, axis=1)
    angle = np.degrees(np.arccos(np.clip(np.abs(span[:, 2]) / length, 0, 1)))
    tension = vtk_to_numpy(poly.GetCellData().GetArray("tension"))
    broken = vtk_to_numpy(poly.GetCellData().GetArray("broken"))
    return float(best.get("timestep")), tension, angle, length, broken


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--run", action="append", required=True, help="LABEL:FIBRE_FRACTION:WALLS.csv[:FIBRES.pvd]")
    ap.add_argument("--box", default="box", help="the box wall's name (faces BOX.xmin ... BOX.zmax)")
    ap.add_argument("--summary", required=True)
    ap.add_argument("--curves", required=True)
    ap.add_argument("--curves-csv")
    ap.add_argument("--gain")
    ap.add_argument("--fibres")
    ap.add_argument("--fibre-area", type=float, default=0.0, help="fibre cross-section [m^2]: mean fibre stress in the summary")
    a = ap.parse_args()

    runs = []
    for spec in a.run:
        parts = spec.split(":")
        if len(parts) not in (3, 4):
            sys.exit(f"--run {spec}: expected LABEL:FIBRE_FRACTION:WALLS.csv[:FIBRES.pvd]")
        h = history(parts[2], a.box)
        runs.append(dict(label=parts[0], rho=float(parts[1]), h=h, s=summarise(h), pvd=parts[3] if len(parts) == 4 else None))
    base = min(runs, key=lambda r: r["rho"])
    kp_base = (1 + np.sin(np.radians(base["s"]["phi_peak"]))) / (1 - np.sin(np.radians(base["s"]["phi_peak"])))

    fig, (ax_q, ax_v) = plt.subplots(1, 2, figsize=(11, 4.5), dpi=110)
    curve_rows = []
    for r in runs:
        h = r["h"]
        ax_q.plot(100 * h["eps_a"], h["q"] / 1e3, label=r["label"])
        ax_v.plot(100 * h["eps_a"], 100 * h["eps_v"], label=r["label"])
        curve_rows += [[r["label"], r["rho"], *vals] for vals in zip(h["time"], h["eps_a"], h["eps_v"], h["sigma_1"], h["sigma_3"], h["q"])]
    ax_q.set_xlabel("axial strain [%]"), ax_q.set_ylabel("deviator stress q = σ1 − σ3 [kPa]"), ax_q.legend()
    ax_v.set_xlabel("axial strain [%]"), ax_v.set_ylabel("volumetric strain [%] (compression positive)"), ax_v.legend()
    ax_q.set_title("Deviator stress"), ax_v.set_title("Volumetric strain")
    save_atomically(fig, a.curves)
    if a.curves_csv:
        write_csv(a.curves_csv, ["run", "fibre_fraction", "time_s", "axial_strain", "volumetric_strain", "sigma_1_Pa", "sigma_3_Pa", "q_Pa"], curve_rows)

    rows = []
    if a.fibres:
        fig_f, ax_f = plt.subplots(figsize=(6.5, 4.5), dpi=110)
    for r in runs:
        s = r["s"]
        gain = s["q_peak"] / base["s"]["q_peak"] - 1
        c = extension_cone(s["dilatancy_peak"])
        mean_stress = np.nan
        if r["pvd"]:
            t_peak = r["h"]["time"][int(np.argmax(r["h"]["q"]))]
            t_frame, tension, angle, length, broken = fibre_frame(r["pvd"], t_peak)
            lengthening = angle > np.degrees(np.arccos(c))
            if a.fibre_area > 0 and lengthening.any():  # length-weighted mean stress of the fibres in the extension cone
                mean_stress = np.sum(tension[lengthening] * length[lengthening]) / np.sum(length[lengthening]) / a.fibre_area
            if a.fibres:
                ax_f.scatter(angle, tension, s=4, alpha=0.4, label=f"{r['label']} (t = {t_frame:.3g} s, {int(broken.sum())} broken)")
                edges = np.linspace(0, 90, 10)
                mid = (edges[1:] + edges[:-1]) / 2
                means = [tension[(angle >= lo) & (angle < hi)].mean() if ((angle >= lo) & (angle < hi)).any() else np.nan
                         for lo, hi in zip(edges[:-1], edges[1:])]
                ax_f.plot(mid, means, marker="o")
                ax_f.axvline(np.degrees(np.arccos(c)), ls=":", color="grey")
        predicted = r["rho"] * mean_stress * fibre_factor(c, kp_base) if np.isfinite(mean_stress) else np.nan
        rows.append([r["label"], r["rho"], s["q_peak"], s["eps_peak"], s["sigma3_peak"], s["phi_peak"], s["q_res"], s["phi_res"], s["eps_v_end"],
                     s["dilatancy_peak"], gain, mean_stress, predicted, predicted / base["s"]["q_peak"] if np.isfinite(predicted) else np.nan,
                     *s["q_bands"]])
        print(f"{r['label']}: peak q {s['q_peak'] / 1e3:.1f} kPa at {100 * s['eps_peak']:.2f} % (sigma_3 {s['sigma3_peak'] / 1e3:.1f} kPa), "
              f"phi_peak {s['phi_peak']:.2f} deg, residual q {s['q_res'] / 1e3:.1f} kPa, phi_res {s['phi_res']:.2f} deg, "
              f"gain {100 * gain:+.1f} %, mean fibre stress in extension {mean_stress / 1e6:.3g} MPa, eq. P69 gain {100 * rows[-1][13]:+.1f} %")
    write_csv(a.summary, ["run", "fibre_fraction", "q_peak_Pa", "axial_strain_at_peak", "sigma_3_at_peak_Pa", "phi_peak_deg", "q_residual_Pa",
                          "phi_residual_deg", "volumetric_strain_end", "dilatancy_at_peak", "gain", "mean_fibre_stress_Pa",
                          "predicted_dq_Pa", "predicted_gain", *[f"q_mean_{100 * lo:g}_{100 * hi:g}_percent_Pa" for lo, hi in BANDS]], rows)
    if a.fibres:
        ax_f.set_xlabel("fibre segment's angle from the axis [deg]"), ax_f.set_ylabel("tension [N]")
        ax_f.set_title("Fibre tension at the peak (dotted: edge of the extension cone, eq. P67)", fontsize=9)
        ax_f.legend(fontsize=8)
        save_atomically(fig_f, a.fibres)
    if a.gain:
        fig_g, ax_g = plt.subplots(figsize=(6, 4.5), dpi=110)
        rho = np.array([r[1] for r in rows])
        ax_g.plot(100 * rho, 100 * np.array([r[10] for r in rows]), "o-", label="measured: peak q / peak q without fibres − 1")
        ax_g.plot(100 * rho, 100 * np.nan_to_num(np.array([r[13] for r in rows])), "s--",
                  label="Michalowski & Zhao (eq. P69) with the measured fibre stress")
        ax_g.set_xlabel("fibre volume fraction [%]"), ax_g.set_ylabel("gain in peak deviator stress [%]")
        ax_g.legend(fontsize=8)
        save_atomically(fig_g, a.gain)


if __name__ == "__main__":
    main()
