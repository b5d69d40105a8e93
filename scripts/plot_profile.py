#!/usr/bin/env python3
"""Plot a post-macro displacement profile (CSV) to PNG: mean displacement components versus height."""
import sys

from debian_python import ensure  # noqa: E402

ensure("numpy", "matplotlib")

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from post_table import AXIS_WORDS, read_table, save_atomically, source_note  # noqa: E402


def labels(title: str, axis: str) -> dict:
    """The figure's words: a title that says what is plotted, the axes with their units."""
    return {"title": f"Mean displacement of the particles in slabs along {axis}", "subtitle": source_note(title),
            "xlabel": "mean displacement [mm]", "ylabel": f"{AXIS_WORDS[axis]} of the slab centre [mm]"}


def main(csv_path: str, png_path: str) -> None:
    title, header, data, col = read_table(csv_path)
    axis = header[0].split("_")[0]
    words = labels(title, axis)
    fig, ax = plt.subplots(figsize=(5, 4.5), dpi=120)
    used = data[:, col["count"]] > 0
    z = data[used, 0] * 1e3
    for name, label in (("mean_ux", "$u_x$"), ("mean_uy", "$u_y$"), ("mean_uz", "$u_z$"), ("mean_norm_u", "$|u|$")):
        ax.plot(data[used, col[name]] * 1e3, z, marker="o", label=label)
    ax.axvline(0, color="grey", lw=0.8)
    ax.set_xlabel(words["xlabel"])
    ax.set_ylabel(words["ylabel"])
    fig.suptitle(words["title"], fontsize=10)
    ax.set_title(words["subtitle"], fontsize=6, wrap=True)
    ax.legend()
    save_atomically(fig, png_path)
    plt.close(fig)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: plot_profile.py PROFILE.csv OUT.png")
    main(sys.argv[1], sys.argv[2])
