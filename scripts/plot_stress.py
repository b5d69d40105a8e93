#!/usr/bin/env python3
"""Plot a post-macro stress table (CSV) to PNG (matplotlib, Agg backend: no display needed).

- a stress profile (--stress-csv): the normal stresses sxx, syy, szz and the pressure p against
  the profile axis (slabs with no particle left out);
- box averages (--average-csv): sxx, syy, szz, p and q for each region, as bars.

Stresses in Pa with post-macro's sign convention: tension positive, so a compressed sample has
negative normal stresses and a positive pressure p = -trace/3 (docs/post.md).

usage: plot_stress.py TABLE.csv OUT.png
"""
import sys

from debian_python import ensure  # noqa: E402

ensure("numpy", "matplotlib")

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from post_table import AXIS_WORDS, finish_figure, plot_slab_profile, read_table, source_note  # noqa: E402


def labels(title: str, header) -> dict:
    """The figure's words: a title that says what is plotted, the axes with their units."""
    part = "contact + kinetic stress" if "contact + kinetic" in title else "contact stress"
    if header[0] == "region":
        return {"title": f"Mean {part} in each averaging box", "subtitle": source_note(title), "xlabel": "averaging box",
                "ylabel": "stress [Pa] (tension positive; p, q positive in compression)"}
    axis = header[0].split("_")[0]
    return {"title": f"Mean {part} in slabs along {axis}", "subtitle": source_note(title),
            "xlabel": "stress [Pa] (tension positive; p positive in compression)", "ylabel": f"{AXIS_WORDS[axis]} of the slab centre [mm]"}


def main(csv_path: str, png_path: str) -> None:
    title, header, data, col = read_table(csv_path)
    words = labels(title, header)
    fig, ax = plt.subplots(figsize=(5.5, 4.5), dpi=120)
    names = (("sxx", r"$\sigma_{xx}$"), ("syy", r"$\sigma_{yy}$"), ("szz", r"$\sigma_{zz}$"), ("pressure", "pressure $p$"))
    if header[0] == "region":  # box averages
        x = np.arange(len(data))
        shown = names + (("q", "von Mises $q$"),)
        width = 0.8 / len(shown)
        for k, (name, label) in enumerate(shown):
            ax.bar(x + (k - (len(shown) - 1) / 2) * width, data[:, col[name]], width, label=label)
        ax.set_xticks(x, [f"region {int(r)}" for r in data[:, 0]])
        ax.set_ylabel(words["ylabel"])
        ax.set_xlabel(words["xlabel"])
        ax.axhline(0, color="grey", lw=0.8)
    else:  # profile along an axis
        plot_slab_profile(ax, data, col, names, words)
    finish_figure(fig, ax, words, png_path)
    plt.close(fig)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: plot_stress.py TABLE.csv OUT.png")
    main(sys.argv[1], sys.argv[2])
