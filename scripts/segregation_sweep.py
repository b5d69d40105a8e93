#!/usr/bin/env python3
"""Rise of the large sphere against the shaking (workflows/segregation/sweep.toml): for each run
from the same settled bed, the cycle at which the intruder's top first comes within one small
diameter of the bed's surface at rest, and whether it stays there. Writes a table and a PNG of
the per-cycle mean height of every run.
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


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--start", required=True, help="the settled checkpoint all runs start from")
    ap.add_argument("--run", nargs=4, action="append", required=True, metavar=("NAME", "TRACK", "FREQUENCY", "GAMMA"),
                    help="a run: its name, its --track CSV, frequency [Hz] and peak acceleration [g]")
    ap.add_argument("--intruder", type=int, default=0)
    ap.add_argument("--table", required=True, help="output CSV")
    ap.add_argument("--png", required=True)
    a = ap.parse_args()

    start = load(a.start)
    k0 = np.searchsorted(start["id"], a.intruder)
    big_r = start["r"][k0]
    small_d = 2 * np.median(start["r"])
    surface, _ = surface_height(start, [a.intruder])
    rows = []
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=120)
    for name, track, freq, gamma in a.run:
        f, g = float(freq), float(gamma)
        t, z = read_tracks([track], a.intruder)
        mid, zc = per_cycle_height(t, z, start["t"], f)
        arrival, stay = arrival_cycle(mid, zc, big_r, surface, small_d)
        amplitude = g * 9.81 / (2 * math.pi * f) ** 2
        rows.append((name, f, g, amplitude, amplitude / small_d, mid[-1] + 0.5, zc[0], zc.max(), zc[-1], arrival,
                     arrival / f, stay))
        print(f"segregation-sweep: {name}: {g:g} g at {f:g} Hz (amplitude {amplitude * 1e3:.2f} mm): "
              + (f"reaches the surface after {arrival:.0f} cycles ({arrival / f:.1f} s), stays {stay:.0%} of the later cycles"
                 if np.isfinite(arrival) else f"does not reach the surface in {mid[-1] + 0.5:.0f} cycles, "
                 f"highest {zc.max() * 1e3:.1f} mm, ends at {zc[-1] * 1e3:.1f} mm"))
        ax.plot(mid, zc * 1e3, lw=1.2, label=f"{g:g} g, {f:g} Hz (A = {amplitude * 1e3:.1f} mm)")
    write_csv(a.table, ["run", "frequency_hz", "gamma", "amplitude_m", "amplitude_over_small_diameter", "cycles",
                        "centre_first_cycle_m", "centre_highest_m", "centre_last_cycle_m", "reaches_surface_after_cycles",
                        "reaches_surface_after_s", "fraction_of_later_cycles_at_surface"], rows)
    ax.axhline((surface - big_r - small_d) * 1e3, color="C3", ls=":", lw=1,
               label="top within one small diameter of the surface at rest")
    ax.set_xlabel("cycles")
    ax.set_ylabel("large sphere's centre, per-cycle mean [mm]")
    ax.set_title("Brazil-nut rise against the shaking (same settled bed)", fontsize=9)
    ax.legend(fontsize=7)
    save_atomically(fig, a.png)
    plt.close(fig)


if __name__ == "__main__":
    main()
