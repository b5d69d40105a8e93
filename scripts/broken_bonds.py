#!/usr/bin/env python3
"""The broken-bond fraction against time, from run-stage's health log (OUT.health.csv): a CSV and
a PNG. The fraction at a row is broken / (intact + broken), with `bonds` the intact bonds and
`bonds_broken` those broken since the stage began (so intact + broken is the number the stage
started with, whatever the row).

usage: broken_bonds.py RUN.health.csv OUT.csv OUT.png
"""
import sys

from debian_python import ensure  # noqa: E402

ensure("numpy", "matplotlib")

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from run_log_figure import read_columns  # noqa: E402
from post_table import save_atomically, write_csv  # noqa: E402


def broken_fraction(c):
    """(time, intact, broken, fraction) of a health log's columns; fraction NaN without bonds."""
    intact, broken = c["bonds"], np.nan_to_num(c["bonds_broken"])
    total = intact + broken
    with np.errstate(invalid="ignore", divide="ignore"):
        fraction = np.where(total > 0, broken / np.where(total > 0, total, 1), np.nan)
    return c["time_s"], intact, broken, fraction


def main(health_csv: str, out_csv: str, png_path: str) -> None:
    t, intact, broken, fraction = broken_fraction(read_columns(health_csv))
    if not np.any(intact + broken > 0):
        sys.exit(f"{health_csv}: no bonds in this stage (a stage action \"bond\" makes them)")
    write_csv(out_csv, ["time_s", "bonds_intact", "bonds_broken", "broken_fraction"],
              [[f"{a:.9g}", int(b), int(c), f"{d:.9g}"] for a, b, c, d in zip(t, intact, broken, fraction)])
    fig, ax = plt.subplots(figsize=(6.5, 4.2), dpi=110)
    ax.plot(t * 1e3, 100 * fraction, color="C3")
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("broken bonds [% of those at the start]")
    ax.set_ylim(0, max(1.0, 105 * np.nanmax(fraction)))
    ax.grid(alpha=0.3)
    ax.set_title(f"{int(intact[0] + broken[0])} bonds at the start, {int(broken[-1])} broken at {t[-1] * 1e3:.4g} ms",
                 fontsize=10)
    save_atomically(fig, png_path)
    plt.close(fig)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit("usage: broken_bonds.py RUN.health.csv OUT.csv OUT.png")
    main(*sys.argv[1:])
