#!/usr/bin/env python3
"""Vibrated bed (thesis §4.6): what the bed does under 25 Hz, 6 g shaking, from run-stage's outputs.

Reads the floor's force (run-stage --wall-forces CSV, wall box.zmin), the stroboscopic VTK frames
(one per cycle, same phase; a .pvd series) and the checkpoint at the end of the vibration, and
measures:
  - period doubling of the bed's flight: the floor's impulse per cycle alternates between about
    2·M·g·T and about 0 when the bed hits the floor every other cycle; compared with the completely
    inelastic bouncing ball (the model of Brennen, Ghosh & Wassgren 1996), which at Γ = 6 leaves
    the plate where its acceleration reaches −g (sin φ = 1/Γ) and flies for nearly two cycles;
  - the free surface h(x) (and the underside of the bed) at the same phase in successive cycles:
    standing waves or arches that switch at every impact show as a shape that inverts from one
    impact to the next: with impacts every other cycle, the correlation of profiles two cycles
    apart is negative and of profiles four cycles apart positive (waves at f/4; with impacts every
    cycle, at lags 1 and 2: f/2 waves);
  - heaping: the time-averaged surface near the side walls against the centre;
  - convection: the mean displacement field of the spheres over the run.
Writes a summary table (key,value,unit), the profiles and the displacement field as CSV, and
PNG plots (optionally the eight-phases-per-cycle frames of a second stage). --skip cycles at the
start (the bed still settling into its regime) are left out of every statistic.
"""
import argparse
import csv
import math
import os
import xml.etree.ElementTree as ET

from debian_python import ensure  # noqa: E402

ensure("h5py", "numpy", "matplotlib", "vtk")

import h5py
import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from post_table import save_atomically, write_csv  # noqa: E402

COLUMN = 0.005     # m: width of the columns of the surface profile, about five diameters
TOP_Q = 95         # percentile of the sphere tops in a column taken as the free surface: a few
BOTTOM_Q = 5       # spheres thrown far above the bed (or below it) do not move it


def read_series(pvd):
    """(times, file paths) of a ParaView .pvd series, in time order."""
    root = ET.parse(pvd).getroot()
    base = os.path.dirname(pvd)
    items = sorted((float(d.get("timestep")), os.path.join(base, d.get("file"))) for d in root.iter("DataSet"))
    return np.array([t for t, _ in items]), [p for _, p in items]


def read_frame(path):
    """Particle centres, radii and ids of one .vtu frame, sorted by id."""
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    out = r.GetOutput()
    x = vtk_to_numpy(out.GetPoints().GetData()).astype(float)
    rad = vtk_to_numpy(out.GetPointData().GetArray("radius")).astype(float)
    ids = vtk_to_numpy(out.GetPointData().GetArray("id")).astype(np.int64)
    order = np.argsort(ids)
    return x[order], rad[order], ids[order]


def inelastic_ball(gamma):
    """Completely inelastic ball on a plate z_p = A·sin φ (φ = ωt): it leaves the plate where the
    plate's acceleration −A·ω²·sin φ reaches −g, sin φ0 = 1/Γ, with the plate's velocity, and flies
    ballistically. Returns (φ0, landing φ), in cycles (φ/2π)."""
    phi0 = math.asin(1.0 / gamma)
    gap = lambda p: math.sin(phi0) + math.cos(phi0) * (p - phi0) - (p - phi0) ** 2 / (2 * gamma) - math.sin(p)
    p = phi0 + 1e-3
    while gap(p + 1e-3) > 0:      # march to the first sign change, then bisect
        p += 1e-3
    lo, hi = p, p + 1e-3
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if gap(mid) > 0 else (lo, mid)
    return phi0 / (2 * math.pi), lo / (2 * math.pi)


def floor_analysis(path, t0, period, weight, skip):
    """The particles' force on the floor (box.zmin) per sample, and its impulse over windows one
    cycle long centred on whole cycles (phases k − ½ to k + ½: the bed lands and leaves within one
    window, near phase 0), in units of the weight's impulse per cycle M·g·T."""
    t, f, lid = [], [], 0
    with open(path) as fh:
        for r in csv.DictReader(fh):
            if r["wall"] == "box.zmin":
                t.append(float(r["time_s"]))
                f.append(-float(r["fz_N"]))   # the particles push the floor down: fz < 0
            elif r["wall"] == "box.zmax":
                lid = max(lid, int(r["contacts"]))
    phase = (np.array(t) - t0) / period
    force = np.array(f) / weight
    dt = np.diff(phase, prepend=phase[0] - (phase[1] - phase[0]))   # sample spacing, cycles
    win = np.floor(phase + 0.5).astype(int)
    windows = np.arange(max(skip, 1), win.max())    # whole windows only
    impulse = np.array([np.sum(force[win == k] * dt[win == k]) for k in windows])
    # Fourier components of the force at f/2 and f over an even number of cycles after the skipped
    # ones, relative to its mean: a bed hitting the floor every other cycle (short impacts) gives
    # about 1 at f/2, a bed hitting every cycle about 0 (its force repeats every cycle).
    span = (phase >= skip) & (phase < skip + 2 * ((phase.max() - skip) // 2))
    comp = lambda nu: float(abs(np.sum(force[span] * np.exp(-2j * np.pi * nu * phase[span]))) / np.sum(force[span]))
    return phase, force, windows, impulse, lid, comp(0.5), comp(1.0), float(np.mean(force[span]))


def column_profiles(x, r, z_floor, width):
    """Free surface (TOP_Q percentile of sphere tops) and underside (BOTTOM_Q percentile of sphere
    bottoms) per column, heights above the floor."""
    edges = np.arange(0.0, width + 1e-12, COLUMN)
    col = np.clip(((x[:, 0]) / COLUMN).astype(int), 0, len(edges) - 2)
    top = np.array([np.percentile(x[col == c, 2] + r[col == c], TOP_Q) for c in range(len(edges) - 1)]) - z_floor
    bot = np.array([np.percentile(x[col == c, 2] - r[col == c], BOTTOM_Q) for c in range(len(edges) - 1)]) - z_floor
    return 0.5 * (edges[:-1] + edges[1:]), top, bot


def mean_corr(profiles, lag):
    """Mean correlation coefficient between the shapes (mean removed) of profiles lag frames apart."""
    d = profiles - profiles.mean(axis=1, keepdims=True)
    c = [np.corrcoef(d[i], d[i + lag])[0, 1] for i in range(len(d) - lag)]
    return float(np.mean(c)) if c else float("nan")


def dominant_mode(profiles, width):
    """Standing-wave mode m (shape ~ cos(m·π·x/L) between the side walls) carrying most of the
    power of the profiles' shapes, averaged over frames; wavelength 2L/m."""
    d = profiles - profiles.mean(axis=1, keepdims=True)
    xc = (np.arange(d.shape[1]) + 0.5) / d.shape[1]
    modes = np.arange(1, d.shape[1] // 2)
    if modes.size == 0:                      # a box too narrow for waves (the test's)
        return 0, float("nan")
    power = [np.mean((d @ np.cos(m * np.pi * xc)) ** 2) for m in modes]
    m = int(modes[int(np.argmax(power))])
    return m, 2 * width / m


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--end", required=True, help="checkpoint at the end of the vibration (reference positions = its start)")
    ap.add_argument("--wall-forces", required=True, help="run-stage --wall-forces CSV of the vibration stage")
    ap.add_argument("--frames", required=True, help=".pvd series of the vibration stage, one frame per cycle")
    ap.add_argument("--strobe", help=".pvd series of a later stage with several frames per cycle (optional)")
    ap.add_argument("--frequency", type=float, required=True, help="vibration frequency f [Hz]")
    ap.add_argument("--acceleration", type=float, required=True, help="peak acceleration of the box [m/s^2]")
    ap.add_argument("--skip", type=int, default=10, help="cycles left out at the start (default 10)")
    ap.add_argument("--summary", required=True, help="summary CSV (key,value,unit)")
    ap.add_argument("--surface", help="CSV of the surface profiles, one row per frame and column")
    ap.add_argument("--displacement", help="CSV of the mean displacement field on 5 mm cells")
    ap.add_argument("--png", required=True)
    ap.add_argument("--strobe-png", help="PNG of the --strobe frames (two cycles)")
    a = ap.parse_args()

    with h5py.File(a.end, "r") as f:
        mass = float(np.sum(f["particles/mass"][()]))
        g = float(np.linalg.norm(f["state/gravity"][()]))
        dt = float(f["state/dt"][0])
        n = int(f["particles/id"].shape[0])
        walls = f["walls/base_vertices"][()].reshape(-1, 3)
    width = float(walls[:, 0].max() - walls[:, 0].min())
    period = 1.0 / a.frequency
    gamma = a.acceleration / g
    amp = a.acceleration / (2 * math.pi * a.frequency) ** 2
    times, paths = read_series(a.frames)
    t0 = times[0]                                   # the stage (and the vibration) starts at frame 0
    cycles = np.rint((times - t0) / period).astype(int)
    phase_err = float(np.max(np.abs((times - t0) / period - cycles)))
    floor_z = lambda t: amp * math.sin(2 * math.pi * a.frequency * (t - t0))

    # --- The floor: period doubling of the impacts, against the inelastic ball. ---
    phase, force, windows, impulse, lid_contacts, half_f, one_f, mean_force = floor_analysis(
        a.wall_forces, t0, period, mass * g, a.skip)
    ball_off, ball_land = inelastic_ball(gamma)
    alternation = np.abs(np.diff(impulse)) / (impulse[:-1] + impulse[1:])
    heavy = impulse > 1.0                           # windows holding an impact (more than M·g·T)
    steady = phase >= windows[0] - 0.5
    # Last phase of each heavy window with the bed still pressing on the floor (> 5 % of its weight):
    # the bed leaves there; the ball model leaves at ball_off.
    leave, land = [], []
    for k in windows[heavy]:
        w = (phase >= k - 0.5) & (phase < k + 0.5)
        on = phase[w][force[w] > 0.05]
        if on.size:
            leave.append(on.max() - k)
        c = np.cumsum(force[w]) / np.sum(force[w])  # impulse centroid: when the bed hits
        land.append(phase[w][np.searchsorted(c, 0.5)] - k)
    gaps = np.diff(windows[heavy])

    # --- Stroboscopic profiles (same phase every cycle). ---
    prof_rows, tops, bots, kept = [], [], [], []
    first = last = None
    max_top, spray = 0.0, 0
    for t, p, k in zip(times, paths, cycles):
        x, r, ids = read_frame(p)
        zf = floor_z(t)
        xc, top, bot = column_profiles(x, r, zf, width)
        prof_rows += [(k, f"{t:.9g}", f"{xx:.6g}", f"{hh:.6g}", f"{bb:.6g}") for xx, hh, bb in zip(xc, top, bot)]
        if k >= a.skip:
            tops.append(top)
            bots.append(bot)
            kept.append(k)
            first = (k, x, ids) if first is None else first
            if (k - first[0]) % 4 == 0:          # the last frame at the same point of a 4-cycle pattern
                last = (k, x, ids)
        max_top = max(max_top, float(np.max(x[:, 2] + r)) - zf)
        spray += int(np.sum(x[:, 2] + r - zf > 0.05))
    tops, bots = np.array(tops), np.array(bots)
    mean_top = tops.mean(axis=0)
    near_wall = (xc < 0.01) | (xc > width - 0.01)
    centre = np.abs(xc - width / 2) < 0.02
    mode, wavelength = dominant_mode(tops, width)
    level = tops.mean(axis=1)

    # --- Convection: displacement between the first kept frame and the last one a multiple of four
    # cycles later (the same point of the bed's two-cycle flight and of the waves' four-cycle
    # pattern), per 5 mm cell of the starting position, the bed's mean displacement removed. ---
    (k1, x1, id1), (k2, x2, id2) = first, last
    assert np.array_equal(id1, id2), "the frames must hold the same particles"
    d = x2 - x1
    d -= d.mean(axis=0)
    nz = int(math.ceil(float(np.max(x1[:, 2])) / COLUMN))
    ci = np.clip((x1[:, 0] / COLUMN).astype(int), 0, len(xc) - 1)
    cj = np.clip((x1[:, 2] / COLUMN).astype(int), 0, nz - 1)
    field = []
    for i in range(len(xc)):
        for j in range(nz):
            m = (ci == i) & (cj == j)
            if m.sum() >= 10:                     # leave out the dilute spray above the bed
                field.append((xc[i], (j + 0.5) * COLUMN, int(m.sum()), d[m, 0].mean(), d[m, 2].mean()))
    field = np.array(field)
    wall_band = (x1[:, 0] < 0.005) | (x1[:, 0] > width - 0.005)    # within 5 mm of a side wall
    middle = np.abs(x1[:, 0] - width / 2) < 0.02
    span = max(k2 - k1, 1)

    rows = [
        ("particles", n, "-"),
        ("time_step", dt, "s"),
        ("steps_per_cycle", period / dt, "-"),
        ("gamma", gamma, "-"),
        ("amplitude", amp, "m"),
        ("frames_phase_error_max", phase_err, "cycles"),
        ("cycles_left_out", a.skip, "cycles"),
        ("floor_force_mean", mean_force, "M*g"),
        ("floor_force_component_half_f", half_f, "of mean"),
        ("floor_force_component_f", one_f, "of mean"),
        ("floor_impulse_alternation", float(np.mean(alternation)), "-"),
        ("floor_windows_with_impact", float(np.mean(heavy)), "-"),
        ("floor_impact_spacing_mean", float(np.mean(gaps)) if gaps.size else float("nan"), "cycles"),
        ("floor_impulse_per_impact", float(np.mean(impulse[heavy])) if heavy.any() else float("nan"), "M*g*T"),
        ("floor_impulse_per_impact_min", float(np.min(impulse[heavy])) if heavy.any() else float("nan"), "M*g*T"),
        ("floor_impulse_per_impact_max", float(np.max(impulse[heavy])) if heavy.any() else float("nan"), "M*g*T"),
        ("floor_impulse_between_impacts_max", float(np.max(impulse[~heavy])) if (~heavy).any() else float("nan"), "M*g*T"),
        ("ball_leaves_plate_phase", ball_off, "cycles"),
        ("ball_flight", ball_land - ball_off, "cycles"),
        ("ball_lands_phase", ball_land - math.floor(ball_land + 0.5), "cycles"),
        ("bed_leaves_floor_phase", float(np.median(leave)) if leave else float("nan"), "cycles"),
        ("bed_impact_centroid_phase", float(np.median(land)) if land else float("nan"), "cycles"),
        ("lid_contacts_max", lid_contacts, "-"),
        ("highest_sphere_top_above_floor_in_frames", max_top, "m"),
        ("sphere_frames_more_than_50mm_above_floor", spray, "-"),
        ("sphere_frames", n * len(times), "-"),
        ("surface_mean_height", float(level.mean()), "m"),
        ("surface_mean_height_change_1_cycle", float(np.mean(np.abs(np.diff(level)))), "m"),
        ("surface_mean_height_change_2_cycles", float(np.mean(np.abs(level[2:] - level[:-2]))), "m"),
        ("surface_shape_rms", float(np.mean(np.std(tops, axis=1))), "m"),
        ("surface_shape_corr_1_cycle", mean_corr(tops, 1), "-"),
        ("surface_shape_corr_2_cycles", mean_corr(tops, 2), "-"),
        ("surface_shape_corr_4_cycles", mean_corr(tops, 4), "-"),
        ("surface_dominant_mode", mode, "-"),
        ("surface_dominant_wavelength", wavelength, "m"),
        ("underside_shape_rms", float(np.mean(np.std(bots, axis=1))), "m"),
        ("underside_shape_corr_1_cycle", mean_corr(bots, 1), "-"),
        ("underside_shape_corr_2_cycles", mean_corr(bots, 2), "-"),
        ("underside_shape_corr_4_cycles", mean_corr(bots, 4), "-"),
        ("heap_centre_minus_walls", float(mean_top[centre].mean() - mean_top[near_wall].mean()), "m"),
        ("displacement_span", span, "cycles"),
        ("wall_band_mean_dz", float(d[wall_band, 2].mean()), "m"),
        ("wall_band_dz_standard_error", float(d[wall_band, 2].std() / math.sqrt(wall_band.sum())), "m"),
        ("middle_mean_dz", float(d[middle, 2].mean()), "m"),
        ("middle_dz_standard_error", float(d[middle, 2].std() / math.sqrt(middle.sum())), "m"),
        ("mean_abs_displacement", float(np.mean(np.linalg.norm(d, axis=1))), "m"),
    ]
    write_csv(a.summary, ["key", "value", "unit"], rows)
    if a.surface:
        write_csv(a.surface, ["cycle", "time_s", "x_m", "surface_m", "underside_m"], prof_rows)
    if a.displacement:
        write_csv(a.displacement, ["x_m", "z_m", "count", "mean_dx_m", "mean_dz_m"], field.tolist())
    for k, v, u in rows:
        print(f"vibrated-bed: {k} = {v:.6g} {u}")

    # --- Plots. ---
    fig = plt.figure(figsize=(12, 10), dpi=110)
    gs = fig.add_gridspec(3, 2, height_ratios=[1.1, 1, 0.9])
    a1, a2, a3, a4 = fig.add_subplot(gs[0, :]), fig.add_subplot(gs[1, 0]), fig.add_subplot(gs[1, 1]), fig.add_subplot(gs[2, :])
    # The last four frames of the parity in which the bed lies lowest (it has landed): cycles
    # n - 6, n - 4, n - 2, n; colour by cycle // 2, which switches at every impact.
    low = int(np.argmin([bots[p::2].mean() for p in (0, 1)]))
    pick = [i for i in range(len(tops)) if (kept[i] - kept[0]) % 2 == low][-4:]
    for n, i in enumerate(pick):
        style = dict(color="C0" if (kept[i] // 2) % 2 == 0 else "C3", ls="-" if n < 2 else ":")
        a1.plot(xc * 1e3, tops[i] * 1e3, lw=1.4, label=f"cycle {kept[i]}", **style)
        a1.plot(xc * 1e3, bots[i] * 1e3, lw=0.7, **style)
    a1.set_xlabel("x [mm]")
    a1.set_ylabel("height above the floor [mm]")
    a1.set_title(f"free surface (thick, {TOP_Q}th percentile of sphere tops per {COLUMN * 1e3:g} mm column) and underside "
                 f"(thin, {BOTTOM_Q}th percentile of bottoms), phase 0, every other cycle: the pattern switches colour at each impact", fontsize=8)
    a1.legend(fontsize=7, ncol=4)
    a2.bar(windows, impulse, color=["C3" if h else "C0" for h in heavy], width=0.8)
    a2.axhline(1.0, color="k", lw=0.7, ls=":")
    a2.set_xlabel("cycle (window from phase -1/2 to +1/2)")
    a2.set_ylabel("floor impulse / (M g T)")
    a2.set_title(f"floor impulse per cycle; force at f/2: {half_f:.2f} of its mean", fontsize=8)
    two = np.mod(phase[steady] - windows[0], 2.0)    # folded on two cycles
    bins = np.linspace(0, 2, 161)
    idx = np.digitize(two, bins) - 1
    fold = [force[steady][idx == b].mean() if np.any(idx == b) else np.nan for b in range(len(bins) - 1)]
    a3.plot(0.5 * (bins[:-1] + bins[1:]), fold, color="C0", lw=1.2, label="floor force, mean over two-cycle periods")
    # The ball model started in the first window with an impact: where it leaves and lands.
    k_hit = windows[heavy][0] if heavy.any() else windows[0]
    a3.axvline(np.mod(k_hit - windows[0] + ball_off, 2.0), color="C2", lw=0.8, ls="--")
    a3.axvline(np.mod(k_hit - windows[0] + ball_land, 2.0), color="C3", lw=0.8, ls="--",
               label="inelastic ball: leaves (green), lands (red)")
    a3.set_xlabel(f"phase [cycles] from cycle {windows[0]}, folded on two cycles")
    a3.set_ylabel("floor force / (M g)")
    a3.set_yscale("symlog", linthresh=1.0)
    a3.legend(fontsize=7)
    q = a4.quiver(field[:, 0] * 1e3, field[:, 1] * 1e3, field[:, 3] * 1e3, field[:, 4] * 1e3, field[:, 2],
                  cmap="viridis", angles="xy", scale_units="xy", scale=1.0)
    a4.set_xlabel("x [mm]")
    a4.set_ylabel("z at the start [mm]")
    a4.set_aspect("equal")
    a4.set_title(f"mean displacement of the spheres per 5 mm cell, cycles {k1} to {k2}, the bed's mean removed "
                 "(arrows to scale)", fontsize=8)
    fig.colorbar(q, ax=a4, label="spheres per cell", shrink=0.8)
    save_atomically(fig, a.png)
    plt.close(fig)

    if a.strobe and a.strobe_png:
        st, sp = read_series(a.strobe)
        s0 = st[0]
        per = int(round(period / np.median(np.diff(st))))
        frames = list(zip(st, sp))[: 2 * per]
        fig, axs = plt.subplots(per, 2, figsize=(13, 1.6 * per), dpi=90, sharex=True, sharey=True)
        for i, (t, p) in enumerate(frames):
            x, r, _ = read_frame(p)
            zf = amp * math.sin(2 * math.pi * a.frequency * (t - s0))
            axx = axs[i % per, i // per]
            axx.scatter(x[:, 0] * 1e3, (x[:, 2] - zf) * 1e3, s=1.2, c=r, cmap="viridis", lw=0)
            axx.set_title(f"cycle {i // per}, phase {(t - s0) / period % 1:.3f}", fontsize=7)
            axx.set_ylim(-1, 40)
            axx.set_aspect("equal")
        for axx in axs[-1]:
            axx.set_xlabel("x [mm]")
        fig.suptitle("eight frames per cycle, two cycles (heights above the floor, mm)", fontsize=9)
        save_atomically(fig, a.strobe_png)
        plt.close(fig)


if __name__ == "__main__":
    main()
