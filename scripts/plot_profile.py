#!/usr/bin/env python3
"""Plot a post-macro displacement profile (CSV) to PNG: mean displacement components versus height."""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from post_table import read_table, save_atomically  # noqa: E402


def main(csv_path: str, png_path: str) -> None:
    title, header, data, col = read_table(csv_path)
    axis = header[0].split("_")[0]
    fig, ax = plt.subplots(figsize=(5, 4.5), dpi=120)
    used = data[:, col["count"]] > 0
    z = data[used, 0] * 1e3
    for name, label in (("mean_ux", "$u_x$"), ("mean_uy", "$u_y$"), ("mean_uz", "$u_z$"), ("mean_norm_u", "$|u|$")):
        ax.plot(data[used, col[name]] * 1e3, z, marker="o", label=label)
    ax.axvline(0, color="grey", lw=0.8)
    ax.set_xlabel("mean displacement [mm]")
    ax.set_ylabel(f"{axis} [mm]")
    ax.set_title(title, fontsize=7, wrap=True)
    ax.legend()
    save_atomically(fig, png_path)
    plt.close(fig)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: plot_profile.py PROFILE.csv OUT.png")
    main(sys.argv[1], sys.argv[2])
