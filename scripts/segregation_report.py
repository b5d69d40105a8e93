#!/usr/bin/env python3
"""Brazil-nut segregation (thesis §4.5): how far and how fast the large sphere rises, and the
convection of the small ones, from the checkpoints and run-stage's --track CSV.

Reads the checkpoint at the start of vibration, one after a first span (the thesis's 4.7 s) and
optionally one at the end, plus the intruder's track(s). Writes a summary table (key,value,unit),
the convection profile (mean vertical displacement of the small spheres against their distance
from the nearest side wall) and a two-panel PNG. Heights are absolute: the floor itself moves by
the vibration amplitude (1.9 mm at 20 Hz, 3 g).
"""
import argparse
import csv

from debian_python import ensure  # noqa: E402

ensure("h5py", "numpy", "matplotlib")

import h5py
import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from post_table import save_atomically, write_csv  # noqa: E402


def load(path):
    with h5py.File(path, "r") as f:
        order = np.argsort(f["particles/id"][()])
        walls = f["walls/base_vertices"][()].reshape(-1, 3)
        return {
            "id": f["particles/id"][()][order],
            "x": f["particles/position"][()][order],
            "r": f["particles/radius"][()][order],
            "t": float(f["state/time"][()]),
            "walls": walls,
        }


def surface_height(s, skip, columns=5):
    """Mean over a columns x columns grid of the highest sphere top (z + r) in each column:
    the bed's free surface, leaving out the particles in `skip` (the intruder)."""
    lo = s["walls"][:, :2].min(axis=0)
    hi = s["walls"][:, :2].max(axis=0)
    keep = ~np.isin(s["id"], skip)
    x, top = s["x"][keep], s["x"][keep, 2] + s["r"][keep]
    cell = np.minimum(((x[:, :2] - lo) / (hi - lo) * columns).astype(int), columns - 1)
    tops = [top[(cell[:, 0] == i) & (cell[:, 1] == j)].max() for i in range(columns) for j in range(columns)]
    return float(np.mean(tops)), float(np.max(top))


def read_tracks(paths, intruder):
    rows = []
    for p in paths:
        with open(p) as f:
            for r in csv.DictReader(f):
                if int(r["id"]) == intruder:
                    rows.append((float(r["time_s"]), float(r["z_m"])))
    rows.sort()
    t, z = (np.array(c) for c in zip(*rows))
    keep = np.concatenate(([True], np.diff(t) > 0))  # a stage's first row repeats the last one before
    return t[keep], z[keep]


def per_cycle_height(t, z, t0, frequency):
    """The intruder's centre height averaged over each whole cycle since t0 (64 equally spaced
    phases, since the samples do not divide a cycle evenly): (cycle midpoints, heights)."""
    cycles = (t - t0) * frequency
    cyc = np.arange(int(np.floor(cycles[-1])))
    phases = (np.arange(64) + 0.5) / 64
    return cyc + 0.5, np.array([np.interp(c + phases, cycles, z).mean() for c in cyc])


def arrival_cycle(mid, zc, big_r, surface, small_d):
    """First cycle whose mean puts the intruder's top within one small diameter of `surface`, and
    the fraction of the cycles from then on that stay there (nan, nan if it never gets there)."""
    at = zc + big_r >= surface - small_d
    hit = np.nonzero(at)[0]
    if not hit.size:
        return float("nan"), float("nan")
    return float(mid[hit[0]]), float(at[hit[0]:].mean())


def plot_height(ax, cycles, z, mid, zc, arrival, frequency, title, marks):
    """The intruder's centre against cycles (raw and per-cycle mean), horizontal `marks`
    ((height, linestyle, label), ...) and the arrival cycle if there is one."""
    ax.plot(cycles, z * 1e3, lw=0.4, color="0.6", label="intruder centre")
    ax.plot(mid, zc * 1e3, lw=1.6, color="C0", label="per-cycle mean")
    for height, ls, label in marks:
        ax.axhline(height * 1e3, color="C3", ls=ls, lw=1, label=label)
    if np.isfinite(arrival):
        ax.axvline(arrival, color="C2", lw=1, label=f"reaches the surface: {arrival:.0f} cycles")
    ax.set_xlabel(f"cycles at {frequency:g} Hz")
    ax.set_ylabel("height [mm]")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7, loc="lower right")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--start", required=True, help="checkpoint at the start of vibration")
    ap.add_argument("--span", required=True, help="checkpoint after the first span (convection is measured over it)")
    ap.add_argument("--end", help="checkpoint at the end of the run (default: --span)")
    ap.add_argument("--track", required=True, nargs="+", help="run-stage --track CSV file(s) of the intruder")
    ap.add_argument("--intruder", type=int, default=0, help="particle id of the large sphere")
    ap.add_argument("--frequency", type=float, required=True, help="vibration frequency [Hz]")
    ap.add_argument("--summary", required=True, help="summary CSV (key,value,unit)")
    ap.add_argument("--convection", required=True, help="convection profile CSV")
    ap.add_argument("--png", required=True)
    ap.add_argument("--rise-track", help="track CSV of the same settled bed shaken harder (stage rise)")
    ap.add_argument("--rise-gamma", type=float, default=5.0, help="peak acceleration of that stage [g]")
    a = ap.parse_args()

    start, span = load(a.start), load(a.span)
    end = load(a.end) if a.end else span
    k0 = np.searchsorted(start["id"], a.intruder)
    big_r = start["r"][k0]
    small_d = 2 * np.median(start["r"])
    t, z = read_tracks(a.track, a.intruder)
    t0 = start["t"]
    cycles = (t - t0) * a.frequency

    # Rise: the intruder's top against the bed's free surface (measured at rest at the start, and
    # at the end). Per-cycle means remove the vibration's own up-and-down.
    h_start, _ = surface_height(start, [a.intruder])
    h_end, top_end = surface_height(end, [a.intruder])
    mid, zc = per_cycle_height(t, z, t0, a.frequency)
    arrival, _ = arrival_cycle(mid, zc, big_r, h_end, small_d)

    # Convection over the first span: mean vertical displacement of the small spheres against the
    # distance of their starting position from the nearest side wall.
    lo = start["walls"][:, :2].min(axis=0)
    hi = start["walls"][:, :2].max(axis=0)
    small = start["id"] != a.intruder
    assert np.array_equal(start["id"], span["id"]), "the particles must be the same in both checkpoints"
    dz = span["x"][small, 2] - start["x"][small, 2]
    xy = start["x"][small, :2]
    wall_dist = np.minimum((xy - lo).min(axis=1), (hi - xy).min(axis=1))
    edges = np.arange(0, wall_dist.max() + small_d / 2, small_d / 2)
    profile = []
    for e0, e1 in zip(edges[:-1], edges[1:]):
        m = (wall_dist >= e0) & (wall_dist < e1)
        if m.sum() >= 5:
            profile.append((0.5 * (e0 + e1), m.sum(), dz[m].mean(), np.median(dz[m]), (dz[m] < 0).mean()))
    band = wall_dist < small_d
    core = wall_dist > 3 * small_d
    span_cycles = (span["t"] - t0) * a.frequency
    big_span = span["x"][k0, 2] - start["x"][k0, 2]
    core_rate = dz[core].mean() / span_cycles

    rows = [
        ("vibration_cycles", (end["t"] - t0) * a.frequency, "cycles"),
        ("surface_height_start", h_start, "m"),
        ("surface_height_end", h_end, "m"),
        ("highest_sphere_top_end", top_end, "m"),
        ("intruder_radius", big_r, "m"),
        ("intruder_centre_start", z[0], "m"),
        ("intruder_centre_end", zc[-1], "m"),
        ("intruder_reaches_surface_after", arrival, "cycles"),
        ("span_cycles", span_cycles, "cycles"),
        ("intruder_rise_in_span", big_span, "m"),
        ("wall_band_mean_dz_in_span", dz[band].mean(), "m"),
        ("wall_band_fraction_moving_down", (dz[band] < 0).mean(), "-"),
        ("core_mean_dz_in_span", dz[core].mean(), "m"),
        ("core_fraction_moving_up", (dz[core] > 0).mean(), "-"),
        ("core_rise_rate", core_rate, "m/cycle"),
        ("intruder_rise_rate_in_span", big_span / span_cycles, "m/cycle"),
    ]
    if a.rise_track:
        # The same settled bed shaken harder: arrival against the surface at rest before shaking
        # (a strongly shaken bed is dilated, so its own surface at an instant is no fixed mark).
        rt, rz = read_tracks([a.rise_track], a.intruder)
        rmid, rzc = per_cycle_height(rt, rz, t0, a.frequency)
        r_arrival, r_stay = arrival_cycle(rmid, rzc, big_r, h_start, small_d)
        rows += [
            ("rise_cycles", rmid[-1] + 0.5, "cycles"),
            ("rise_peak_acceleration", a.rise_gamma, "g"),
            ("rise_intruder_centre_end", rzc[-1], "m"),
            ("rise_reaches_surface_after", r_arrival, "cycles"),
            ("rise_fraction_of_later_cycles_at_surface", r_stay, "-"),
        ]
    write_csv(a.summary, ["key", "value", "unit"], rows)
    write_csv(a.convection, ["wall_distance_m", "count", "mean_dz_m", "median_dz_m", "fraction_down"], profile)
    for k, v, u in rows:
        print(f"segregation: {k} = {v:.6g} {u}")

    fig, axes = plt.subplots(1, 3 if a.rise_track else 2, figsize=(15 if a.rise_track else 10, 4.2), dpi=120)
    ax1, ax2 = axes[0], axes[1]
    ax1.axvline(span_cycles, color="0.3", lw=0.8, ls="-.", label="thesis span (4.7 s)")
    plot_height(ax1, cycles, z, mid, zc, arrival, a.frequency, "Large sphere (24 mm) in 8 mm spheres, 3 g",
                [(h_end - big_r, "--", "centre at the surface (end)"), (h_start - big_r, ":", "centre at the surface (start)")])
    p = np.array(profile)
    ax2.plot(p[:, 0] / small_d, p[:, 2] * 1e3, marker="o", label="mean")
    ax2.plot(p[:, 0] / small_d, p[:, 3] * 1e3, marker="s", ls="--", label="median")
    ax2.axhline(0, color="grey", lw=0.8)
    ax2.set_xlabel("distance from the nearest side wall [small diameters]")
    ax2.set_ylabel(f"vertical displacement in {span_cycles:.0f} cycles [mm]")
    ax2.set_title("Convection: down along the walls, up in the centre", fontsize=9)
    ax2.legend(fontsize=7)
    if a.rise_track:
        plot_height(axes[2], (rt - t0) * a.frequency, rz, rmid, rzc, r_arrival, a.frequency, f"The same bed at {a.rise_gamma:g} g",
                    [(h_start - big_r - small_d, ":", "top within one small diameter of the surface at rest")])
    save_atomically(fig, a.png)
    plt.close(fig)


if __name__ == "__main__":
    main()
