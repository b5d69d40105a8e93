#!/usr/bin/env python3
"""Helical flow (thesis §4.3): what a turning auger does to the bed, from run-stage's outputs.

Reads a stage's VTK frames (a .pvd series), its per-wall forces (run-stage --wall-forces CSV) and
the checkpoints at its start and end, and writes:
  - the mass flow rate up the ramp against time: the mass of the particles crossing the horizontal
    annulus z = --plane, --r-in <= r <= --r-out about the axis, upward minus downward, between
    consecutive frames (scripts/plane_flux.py);
  - the torque the drive applies to the turning walls about the axis (minus the particles' torque
    on them) and its power T·ω against time, and the work ∫ T ω dt (trapezoids over the log's rows);
  - checks: the mean flow rate (after --skip seconds of start-up) against the ramp's volumetric
    capacity π (r_out² − r_in²) · pitch · turns per second · bulk density of the bed at the start
    (their ratio: the volumetric efficiency), and the work against the gain of potential and
    kinetic energy of the particles between the two checkpoints (the rest is dissipated by
    friction and damping, so the work must be at least the gain).
"""
import argparse
import csv
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from debian_python import ensure  # noqa: E402

ensure("h5py", "numpy", "matplotlib", "vtk")

import h5py  # noqa: E402
import numpy as np  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from plane_flux import annulus_crossings  # noqa: E402
from post_table import save_atomically, write_csv  # noqa: E402
from vibrated_bed_report import read_frame, read_series  # noqa: E402


def read_state(path):
    """id-sorted (ids, positions, velocities, masses, radii) and the time of a checkpoint."""
    with h5py.File(path, "r") as f:
        ids = f["/particles/id"][:]
        o = np.argsort(ids)
        return (ids[o], f["/particles/position"][:][o], f["/particles/velocity"][:][o], f["/particles/mass"][:][o],
                f["/particles/radius"][:][o], float(f["/state/time"][()]))


def bulk_density(x, m, rad, axis_xy, r_shaft):
    """Mass over volume in a slab of the bed away from the floor and the surface (two largest
    diameters from each; the surface is the 98th percentile of the sphere tops), over the box's
    cross-section (the spheres' extent) less the shaft. Returns (density, solid fraction basis)."""
    d = 2 * rad.max()
    z_lo, z_hi = x[:, 2].min() + 2 * d, np.percentile(x[:, 2] + rad, 98) - 2 * d
    if z_hi <= z_lo:
        raise SystemExit("helical_flow_report: the bed is too shallow to measure its bulk density")
    area = (np.ptp(x[:, 0]) + 2 * rad.mean()) * (np.ptp(x[:, 1]) + 2 * rad.mean()) - math.pi * r_shaft ** 2
    sel = (x[:, 2] >= z_lo) & (x[:, 2] < z_hi)
    return m[sel].sum() / (area * (z_hi - z_lo)), z_lo, z_hi


def flux_series(pvd, ids_ref, mass_ref, axis_xy, r_in, r_out, plane):
    times, paths = read_series(pvd)
    rows, prev = [], None
    for t, p in zip(times, paths):
        x, _, ids = read_frame(p)
        if not np.array_equal(ids, ids_ref):
            raise SystemExit(f"helical_flow_report: {p}: not the particles of the start checkpoint")
        if prev is not None:
            t0, x0 = prev
            up, down, nu, nd = annulus_crossings(x0, x, mass_ref, axis_xy, r_in, r_out, plane)
            rows.append((0.5 * (t0 + t), t - t0, up, down, nu, nd))
        prev = (t, x)
    if not rows:
        raise SystemExit(f"helical_flow_report: {pvd}: fewer than two frames")
    return np.array(rows)


def drive_series(walls_csv, names, axis_xy, omega):
    """Rows (time, drive torque about the axis in the sense of rotation [N m], power [W]) summed over
    the walls `names`; the drive torque is minus the particles' torque on the walls."""
    by_step = {}
    cx, cy = axis_xy
    with open(walls_csv) as f:
        for r in csv.DictReader(f):
            if r["wall"] not in names:
                continue
            tz = float(r["tz_Nm"]) - (cx * float(r["fy_N"]) - cy * float(r["fx_N"]))
            t, s = by_step.get(int(r["step"]), (float(r["time_s"]), 0.0))
            by_step[int(r["step"])] = (t, s + tz)
    if not by_step:
        raise SystemExit(f"helical_flow_report: {walls_csv}: no rows of walls {', '.join(sorted(names))}")
    rows = np.array([by_step[k] for k in sorted(by_step)])
    sense = 1.0 if omega >= 0 else -1.0
    torque = -rows[:, 1] * sense
    return np.column_stack([rows[:, 0], torque, torque * abs(omega)])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--start", required=True, help="checkpoint at the start of the stage")
    ap.add_argument("--end", required=True, help="checkpoint at the end of the stage")
    ap.add_argument("--frames", required=True, help=".pvd series of the stage's particles")
    ap.add_argument("--wall-forces", required=True, help="run-stage --wall-forces CSV of the stage")
    ap.add_argument("--walls", required=True, help="turning walls, comma-separated (e.g. shaft,cap,ramp)")
    ap.add_argument("--rpm", type=float, required=True, help="their speed about the vertical axis [rev/min] (0: at rest)")
    ap.add_argument("--axis", default="0,0", help="x,y of the vertical axis [m] (default 0,0)")
    ap.add_argument("--r-in", type=float, required=True, help="inner radius of the ramp (the shaft) [m]")
    ap.add_argument("--r-out", type=float, required=True, help="outer radius of the ramp [m]")
    ap.add_argument("--pitch", type=float, required=True, help="rise of the ramp per turn [m]")
    ap.add_argument("--plane", type=float, required=True, help="height of the counting plane [m]")
    ap.add_argument("--skip", type=float, default=0.0, help="start-up left out of the mean flow rate [s] (default 0)")
    ap.add_argument("--flux", required=True, help="flow-rate CSV")
    ap.add_argument("--power", required=True, help="torque and power CSV")
    ap.add_argument("--summary", required=True, help="summary CSV (key,value,unit)")
    ap.add_argument("--png", help="plot of flow rate, torque and power against time")
    a = ap.parse_args()
    axis_xy = tuple(float(v) for v in a.axis.split(","))
    omega = 2 * math.pi * a.rpm / 60.0

    ids, x0, v0, m, rad, t_start = read_state(a.start)
    ids1, x1, v1, m1, _, t_end = read_state(a.end)
    if not np.array_equal(ids, ids1):
        raise SystemExit("helical_flow_report: --start and --end hold different particles")
    g = 9.81
    flux = flux_series(a.frames, ids, m, axis_xy, a.r_in, a.r_out, a.plane)
    drive = drive_series(a.wall_forces, set(a.walls.split(",")), axis_xy, omega)

    rho_b, z_lo, z_hi = bulk_density(x0, m, rad, axis_xy, a.r_in)
    capacity = rho_b * math.pi * (a.r_out ** 2 - a.r_in ** 2) * abs(a.pitch) * abs(a.rpm) / 60.0
    steady = flux[:, 0] - t_start >= a.skip
    span = flux[steady, 1].sum()
    net = (flux[steady, 2] - flux[steady, 3]).sum()
    rate = net / span if span > 0 else float("nan")
    work = float(np.trapz(drive[:, 2], drive[:, 0])) if len(drive) > 1 else 0.0
    d_pe = g * float((m * (x1[:, 2] - x0[:, 2])).sum())
    d_ke = 0.5 * float((m * ((v1 ** 2).sum(1) - (v0 ** 2).sum(1))).sum())

    cum = np.cumsum(flux[:, 2] - flux[:, 3])
    write_csv(a.flux, ["time_s", "interval_s", "mass_up_kg", "mass_down_kg", "count_up", "count_down", "net_rate_kg_s", "net_mass_kg"],
              [(f"{r[0]:.6g}", f"{r[1]:.6g}", f"{r[2]:.6g}", f"{r[3]:.6g}", int(r[4]), int(r[5]), f"{(r[2] - r[3]) / r[1]:.6g}", f"{c:.6g}")
               for r, c in zip(flux, cum)])
    work_cum = np.concatenate([[0.0], np.cumsum(0.5 * (drive[1:, 2] + drive[:-1, 2]) * np.diff(drive[:, 0]))])
    write_csv(a.power, ["time_s", "drive_torque_Nm", "power_W", "work_J"],
              [(f"{r[0]:.9g}", f"{r[1]:.6g}", f"{r[2]:.6g}", f"{w:.6g}") for r, w in zip(drive, work_cum)])
    summary = [
        ("duration", t_end - t_start, "s"),
        ("rpm", a.rpm, "rev/min"),
        ("mean_mass_flow", rate, "kg/s"),
        ("mean_mass_flow_from", t_start + a.skip, "s"),
        ("net_mass_up", float(cum[-1]), "kg"),
        ("net_count_up", int(flux[:, 4].sum() - flux[:, 5].sum()), "particles"),
        ("bulk_density", rho_b, "kg/m^3"),
        ("bulk_density_slab_lo", z_lo, "m"),
        ("bulk_density_slab_hi", z_hi, "m"),
        ("capacity", capacity, "kg/s"),
        ("volumetric_efficiency", rate / capacity if capacity > 0 else float("nan"), "-"),
        ("mean_drive_torque", float(drive[:, 1].mean()), "N m"),
        ("mean_power", work / (drive[-1, 0] - drive[0, 0]) if len(drive) > 1 else 0.0, "W"),
        ("work", work, "J"),
        ("potential_energy_gain", d_pe, "J"),
        ("kinetic_energy_gain", d_ke, "J"),
        ("work_less_gains", work - d_pe - d_ke, "J"),
    ]
    write_csv(a.summary, ["key", "value", "unit"], [(k, f"{v:.6g}" if isinstance(v, float) else v, u) for k, v, u in summary])
    for k, v, u in summary:
        print(f"{k:24s} {v:.6g} {u}" if isinstance(v, float) else f"{k:24s} {v} {u}")

    if a.png:
        fig, ax = plt.subplots(3, 1, figsize=(7, 8), sharex=True)
        # A stage's last frame may follow the one before by a few steps: its rate is left off the plot.
        full = flux[:, 1] >= 0.5 * np.median(flux[:, 1])
        ax[0].plot(flux[full, 0], (flux[full, 2] - flux[full, 3]) / flux[full, 1], lw=0.8, label="between frames")
        ax[0].axhline(rate, color="k", ls="--", lw=1, label=f"mean after {a.skip:g} s: {rate:.3g} kg/s")
        ax[0].axhline(capacity, color="r", ls=":", lw=1, label=f"capacity {capacity:.3g} kg/s")
        ax[0].set_ylabel("mass flow rate up [kg/s]")
        ax[0].legend(fontsize=8)
        ax[1].plot(drive[:, 0], drive[:, 1], lw=0.6)
        ax[1].set_ylabel("drive torque [N m]")
        ax[2].plot(drive[:, 0], drive[:, 2], lw=0.6)
        ax[2].set_ylabel("power T·ω [W]")
        ax[2].set_xlabel("time [s]")
        ax[0].set_title(f"auger at {abs(a.rpm):g} rpm: flow through z = {a.plane:g} m, r {a.r_in:g} to {a.r_out:g} m")
        save_atomically(fig, a.png)


if __name__ == "__main__":
    main()
