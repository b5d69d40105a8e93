#!/usr/bin/env python3
"""The produced sand against time: the mass removed by a [stage.sink] (run-stage's OUT.sink.csv,
docs/scene.md), one curve per log, the log's file name as its label.
Usage: plot_sink.py OUT.png LOG.sink.csv [LOG.sink.csv ...]"""
import csv
import os
import sys

from debian_python import ensure  # noqa: E402

ensure("matplotlib")

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from post_table import save_atomically  # noqa: E402


def main(png, logs):
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    for path in logs:
        rows = list(csv.DictReader(open(path)))
        if not rows or "removed_mass_kg" not in rows[0]:
            sys.exit(f"{path}: not a sink log (columns step,time_s,removed,removed_total,removed_mass_kg,particles)")
        t0 = float(rows[0]["time_s"])
        t = [(float(r["time_s"]) - t0) * 1e3 for r in rows]
        m = [float(r["removed_mass_kg"]) * 1e3 for r in rows]
        ax.step(t, m, where="post", label=f"{os.path.basename(path)}: {rows[-1]['removed_total']} grains")
    ax.set_xlabel("time since the stage start [ms]")
    ax.set_ylabel("produced mass [g]")
    ax.legend(fontsize=8)
    save_atomically(fig, png)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2:])
