"""Shared by the plotting and report scripts: reading post-macro's CSV tables, writing CSV tables
and saving figures atomically."""
import csv
import os
import re

import numpy as np


def read_table(csv_path: str):
    """post-macro's CSV: a '# title' line, a header line, then numbers. Returns (title, header,
    data as a 2-D array, column index by name)."""
    with open(csv_path) as f:
        title = f.readline().lstrip("# ").strip()
        header = f.readline().strip().split(",")
    data = np.loadtxt(csv_path, delimiter=",", skiprows=2, ndmin=2)
    return title, header, data, {name: k for k, name in enumerate(header)}


def write_csv(path: str, header, rows) -> None:
    """A CSV table written under a temporary name and renamed: never half-written under `path`."""
    with open(path + ".tmp", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)
    os.replace(path + ".tmp", path)


def save_atomically(fig, png_path: str) -> None:
    """Never a half-written PNG under png_path (make would take it for a finished output)."""
    fig.tight_layout()
    fig.savefig(png_path + ".tmp.png")
    os.replace(png_path + ".tmp.png", png_path)


def plot_slab_profile(ax, data, col, series, words, scale=1.0) -> None:
    """A profile along an axis: each (column, label) of `series` (times `scale`) against the slab
    centre in mm, the slabs with no particle left out, a zero line and the axis words."""
    used = data[:, col["count"]] > 0
    z = data[used, 0] * 1e3
    for name, label in series:
        ax.plot(data[used, col[name]] * scale, z, marker="o", label=label)
    ax.axvline(0, color="grey", lw=0.8)
    ax.set_xlabel(words["xlabel"])
    ax.set_ylabel(words["ylabel"])


def finish_figure(fig, ax, words, png_path: str) -> None:
    """The title, post-macro's source note as a subtitle, the legend; saved atomically."""
    fig.suptitle(words["title"], fontsize=10)
    ax.set_title(words["subtitle"], fontsize=6, wrap=True)
    ax.legend()
    save_atomically(fig, png_path)


AXIS_WORDS = {"x": "position x", "y": "position y", "z": "height z"}


def source_note(title: str) -> str:
    """post-macro's '# title' line as a subtitle: checkpoint paths cut to their file names and the
    unit notes left out (the axis labels give the units)."""
    note = re.sub(r"\S*/([^/\s]+\.h5)", r"\1", title)
    return re.sub(r";\s*lengths.*$", "", note).strip()
