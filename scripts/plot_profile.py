#!/usr/bin/env python3
"""Plot a post-macro displacement profile (CSV) to PNG: mean displacement components versus height."""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main(csv_path: str, png_path: str) -> None:
    with open(csv_path) as f:
        title = f.readline().lstrip("# ").strip()
        header = f.readline().strip().split(",")
    data = np.loadtxt(csv_path, delimiter=",", skiprows=2, ndmin=2)
    col = {name: k for k, name in enumerate(header)}
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
    fig.tight_layout()
    fig.savefig(png_path + ".tmp.png")
    plt.close(fig)
    os.replace(png_path + ".tmp.png", png_path)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: plot_profile.py PROFILE.csv OUT.png")
    main(sys.argv[1], sys.argv[2])
