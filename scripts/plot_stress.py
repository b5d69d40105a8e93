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

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from post_table import read_table, save_atomically  # noqa: E402


def main(csv_path: str, png_path: str) -> None:
    title, header, data, col = read_table(csv_path)
    fig, ax = plt.subplots(figsize=(5.5, 4.5), dpi=120)
    names = (("sxx", r"$\sigma_{xx}$"), ("syy", r"$\sigma_{yy}$"), ("szz", r"$\sigma_{zz}$"), ("pressure", "$p$"))
    if header[0] == "region":  # box averages
        x = np.arange(len(data))
        shown = names + (("q", "$q$"),)
        width = 0.8 / len(shown)
        for k, (name, label) in enumerate(shown):
            ax.bar(x + (k - (len(shown) - 1) / 2) * width, data[:, col[name]], width, label=label)
        ax.set_xticks(x, [f"region {int(r)}" for r in data[:, 0]])
        ax.set_ylabel("stress [Pa] (tension positive)")
        ax.axhline(0, color="grey", lw=0.8)
    else:  # profile along an axis
        axis = header[0].split("_")[0]
        used = data[:, col["count"]] > 0
        z = data[used, 0] * 1e3
        for name, label in names:
            ax.plot(data[used, col[name]], z, marker="o", label=label)
        ax.axvline(0, color="grey", lw=0.8)
        ax.set_xlabel("stress [Pa] (tension positive)")
        ax.set_ylabel(f"{axis} [mm]")
    ax.set_title(title, fontsize=6, wrap=True)
    ax.legend()
    save_atomically(fig, png_path)
    plt.close(fig)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: plot_stress.py TABLE.csv OUT.png")
    main(sys.argv[1], sys.argv[2])
