#!/usr/bin/env python3
"""Plot post-macro's fragment table (--fragments CSV) to PNG (matplotlib, Agg: no display needed).

Left: the grading curve of the fragments, the share of the mass in fragments of equivalent
diameter at most d (a sieve of aperture d), against d in mm on a log axis. Right: how many
fragments hold how many particles. docs/post.md, "Fragments", gives the columns.

usage: plot_fragments.py FRAGMENTS.csv OUT.png
"""
import sys

from debian_python import ensure  # noqa: E402

ensure("numpy", "matplotlib")

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from post_table import read_table, save_atomically, source_note  # noqa: E402


def main(csv_path: str, png_path: str) -> None:
    title, _, data, col = read_table(csv_path)
    d = data[:, col["equivalent_diameter"]] * 1e3
    passing = data[:, col["mass_passing"]]
    particles = data[:, col["particles"]].astype(int)
    order = np.argsort(d, kind="stable")
    fig, (grading, counts) = plt.subplots(1, 2, figsize=(11, 4.5))
    fig.suptitle(f"Fragments: {len(d)} pieces, the largest {particles.max()} particles ({data[0, col['mass']] / data[:, col['mass']].sum():.1%} of the mass)")
    grading.step(d[order], 100 * passing[order], where="post")
    grading.set_xscale("log")
    grading.set_xlabel("equivalent diameter of the fragment [mm]")
    grading.set_ylabel("mass in fragments this size or smaller [%]")
    grading.set_ylim(0, 100)
    grading.grid(True, which="both", alpha=0.3)
    grading.set_title(source_note(title), fontsize=8)
    sizes, how_many = np.unique(particles, return_counts=True)
    counts.bar(np.arange(len(sizes)), how_many)
    counts.set_xticks(np.arange(len(sizes)), [str(s) for s in sizes], rotation=90 if len(sizes) > 12 else 0, fontsize=7)
    counts.set_xlabel("particles in the fragment")
    counts.set_ylabel("number of fragments")
    counts.set_yscale("log")
    save_atomically(fig, png_path)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
