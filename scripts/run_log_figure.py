"""What the plots of run-stage's logs (OUT.health.csv, OUT.energy.csv) share: the columns by name,
a figure of panels sharing the time axis, its title (the file and its steps) and its saving."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from post_table import save_atomically  # noqa: E402


def read_columns(csv_path: str):
    """The columns of a run-stage log by name, as float arrays (an empty cell is NaN)."""
    with open(csv_path) as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    if not body:
        sys.exit(f"{csv_path}: no rows yet")
    return {name: np.array([float(r[k]) if r[k] != "" else np.nan for r in body]) for k, name in enumerate(header)}


def log_figure(rows: int, cols: int, figsize, **grid):
    """A figure of rows x cols panels sharing the time axis."""
    return plt.subplots(rows, cols, figsize=figsize, dpi=110, sharex=True, gridspec_kw=grid or None)


def save_log_figure(fig, csv_path: str, c, png_path: str, more: str = "") -> None:
    """Titles the figure with the log's path and steps (and `more`), writes the PNG, closes it."""
    steps = c["step"]
    fig.suptitle(f"{csv_path}: steps {int(steps[0])} to {int(steps[-1])}{more}", fontsize=9)
    save_atomically(fig, png_path)
    plt.close(fig)


def plot_main(name: str, what: str, main) -> None:
    """The command line of a log plot: NAME RUN.WHAT.csv OUT.png."""
    if len(sys.argv) != 3:
        sys.exit(f"usage: {name} RUN.{what}.csv OUT.png")
    main(sys.argv[1], sys.argv[2])
