#!/usr/bin/env python3
"""Rise of the large sphere over several runs: against the shaking from one settled bed
(workflows/segregation/sweep.toml), or at one shaking from several fills (seeds.toml, one --start
per run). For each run, the cycle at which the intruder's top first comes within one small diameter
of its bed's surface at rest, and whether it stays there. Writes a table, a PNG of the per-cycle
mean height of every run and, with --summary, the spread over the runs.
"""
import argparse
import math

from debian_python import ensure  # noqa: E402

ensure("h5py", "numpy", "matplotlib")

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from post_table import save_atomically, write_csv  # noqa: E402
from segregation_report import arrival_cycle, load, per_cycle_height, read_tracks, surface_height  # noqa: E402


def spread(rows):
    """The spread over the runs (dicts as the table's rows): how many reach the surface, when, and
    where the others are at the end and how fast they still rise."""
    reached = np.array([r["reaches_surface_after_cycles"] for r in rows if np.isfinite(r["reaches_surface_after_cycles"])])
    below = [r for r in rows if not np.isfinite(r["reaches_surface_after_cycles"])]
    out = [("runs", len(rows)), ("runs_reaching_surface", len(reached)), ("cycles_per_run", min(r["cycles"] for r in rows))]
    if reached.size:
        out += [("arrival_cycles_min", reached.min()), ("arrival_cycles_median", float(np.median(reached))),
                ("arrival_cycles_max", reached.max())]
    for key in ("centre_highest_m", "centre_last_cycle_m", "centre_rise_last_100_cycles_m"):
        if below:
            out += [(f"below_{key[:-2]}_min_m", min(r[key] for r in below)), (f"below_{key[:-2]}_max_m", max(r[key] for r in below))]
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--start", required=True, action="append",
                    help="the settled checkpoint the runs start from: once for all runs, or once per run in their order")
    ap.add_argument("--run", nargs=4, action="append", required=True, metavar=("NAME", "TRACK", "FREQUENCY", "GAMMA"),
                    help="a run: its name, its --track CSV, frequency [Hz] and peak acceleration [g]")
    ap.add_argument("--intruder", type=int, default=0)
    ap.add_argument("--table", required=True, help="output CSV")
    ap.add_argument("--png", required=True)
    ap.add_argument("--summary", help="output CSV (key, value): how many runs reach the surface, and the spread")
    ap.add_argument("--title", default="Brazil-nut rise against the shaking (same settled bed)")
    a = ap.parse_args()
    if len(a.start) not in (1, len(a.run)):
        ap.error(f"--start given {len(a.start)} times: give it once, or once per --run ({len(a.run)})")

    rows, thresholds = [], []
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=120)
    for k, (name, track, freq, gamma) in enumerate(a.run):
        start = load(a.start[k if len(a.start) > 1 else 0])
        big_r = start["r"][np.searchsorted(start["id"], a.intruder)]
        small_d = 2 * np.median(start["r"])
        surface, _ = surface_height(start, [a.intruder])
        thresholds.append(surface - big_r - small_d)
        f, g = float(freq), float(gamma)
        t, z = read_tracks([track], a.intruder)
        mid, zc = per_cycle_height(t, z, start["t"], f)
        arrival, stay = arrival_cycle(mid, zc, big_r, surface, small_d)
        amplitude = g * 9.81 / (2 * math.pi * f) ** 2
        # The rise over the last 100 cycles, from the means of 20 cycles (a cycle's mean still wobbles).
        late = float(np.mean(zc[-20:]) - np.mean(zc[-120:-100])) if zc.size >= 120 else float("nan")
        rows.append({"run": name, "frequency_hz": f, "gamma": g, "amplitude_m": amplitude, "amplitude_over_small_diameter": amplitude / small_d,
                     "cycles": mid[-1] + 0.5, "surface_at_rest_m": surface, "centre_first_cycle_m": zc[0], "centre_highest_m": zc.max(),
                     "centre_last_cycle_m": zc[-1], "centre_rise_last_100_cycles_m": late, "reaches_surface_after_cycles": arrival,
                     "reaches_surface_after_s": arrival / f, "fraction_of_later_cycles_at_surface": stay})
        print(f"segregation: {name}: {g:g} g at {f:g} Hz (amplitude {amplitude * 1e3:.2f} mm): "
              + (f"reaches the surface after {arrival:.0f} cycles ({arrival / f:.1f} s), stays {stay:.0%} of the later cycles"
                 if np.isfinite(arrival) else f"does not reach the surface in {mid[-1] + 0.5:.0f} cycles, "
                 f"highest {zc.max() * 1e3:.1f} mm, ends at {zc[-1] * 1e3:.1f} mm, {late * 1e3:+.1f} mm in the last 100 cycles"))
        ax.plot(mid, zc * 1e3, lw=1.2, label=f"{name}: {g:g} g, {f:g} Hz (A = {amplitude * 1e3:.1f} mm)")
    write_csv(a.table, list(rows[0]), [list(r.values()) for r in rows])
    if a.summary:
        write_csv(a.summary, ["key", "value"], spread(rows))
        print("segregation: " + ", ".join(f"{k} {v:.4g}" for k, v in spread(rows)))
    ax.axhline(np.mean(thresholds) * 1e3, color="C3", ls=":", lw=1,
               label="top within one small diameter of the surface at rest"
               + (" (mean over the fills)" if len(a.start) > 1 else ""))
    ax.set_xlabel("cycles")
    ax.set_ylabel("large sphere's centre, per-cycle mean [mm]")
    ax.set_title(a.title, fontsize=9)
    ax.legend(fontsize=7, ncol=2 if len(rows) > 4 else 1)
    save_atomically(fig, a.png)
    plt.close(fig)


if __name__ == "__main__":
    main()
