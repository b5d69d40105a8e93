#!/usr/bin/env python3
"""Plot a post-macro displacement profile (CSV) to PNG: mean displacement components versus height."""
import sys

from debian_python import ensure  # noqa: E402

ensure("numpy", "matplotlib")

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from post_table import AXIS_WORDS, finish_figure, plot_slab_profile, read_table, source_note  # noqa: E402


def labels(title: str, axis: str) -> dict:
    """The figure's words: a title that says what is plotted, the axes with their units."""
    return {"title": f"Mean displacement of the particles in slabs along {axis}", "subtitle": source_note(title),
            "xlabel": "mean displacement [mm]", "ylabel": f"{AXIS_WORDS[axis]} of the slab centre [mm]"}


def main(csv_path: str, png_path: str) -> None:
    title, header, data, col = read_table(csv_path)
    axis = header[0].split("_")[0]
    words = labels(title, axis)
    fig, ax = plt.subplots(figsize=(5, 4.5), dpi=120)
    series = (("mean_ux", "$u_x$"), ("mean_uy", "$u_y$"), ("mean_uz", "$u_z$"), ("mean_norm_u", "$|u|$"))
    plot_slab_profile(ax, data, col, series, words, scale=1e3)
    finish_figure(fig, ax, words, png_path)
    plt.close(fig)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: plot_profile.py PROFILE.csv OUT.png")
    main(sys.argv[1], sys.argv[2])
