#!/usr/bin/env python3
"""Plot run-stage's health log (OUT.health.csv) to PNG: energies, contacts and coordination, the
largest overlap and broken bonds, and the force on each wall, against simulated time."""
import numpy as np
from run_log_figure import log_figure, plot_main, read_columns, save_log_figure


def counts_beside(ax, t, series, ylabel: str) -> None:
    """Counts on a second y axis beside ax's curves, with one legend for both axes."""
    twin = ax.twinx()
    for values, colour, style, label in series:
        twin.plot(t, values, color=colour, ls=style, label=label)
    twin.set_ylabel(ylabel)
    lines = ax.get_lines() + twin.get_lines()
    ax.legend(lines, [line.get_label() for line in lines], fontsize=8)


def main(csv_path: str, png_path: str) -> None:
    c = read_columns(csv_path)
    t = c["time_s"]
    fig, axes = log_figure(2, 2, (10, 7))

    ax = axes[0, 0]
    ax.plot(t, c["kinetic_translation_J"], label="kinetic, translation")
    ax.plot(t, c["kinetic_rotation_J"], label="kinetic, rotation")
    ax.plot(t, c["elastic_bound_J"], label="elastic in contacts (upper bound)")
    ax.set_ylabel("energy [J]")
    if (np.concatenate([c["kinetic_translation_J"], c["elastic_bound_J"]]) > 0).any():
        ax.set_yscale("symlog", linthresh=max(1e-12, 1e-6 * np.nanmax(c["kinetic_translation_J"] + c["elastic_bound_J"])))
    ax.set_title("Energies")
    ax.legend(fontsize=8)

    ax = axes[0, 1]
    ax.plot(t, c["coordination"], color="C0", label="coordination number (pairs only)")
    ax.set_ylabel("coordination number [contacts per particle]")
    ax.set_title("Contacts")
    counts_beside(ax, t, [(c["pair_contacts"], "C1", "--", "particle-particle contacts"),
                          (c["wall_contacts"], "C2", ":", "particle-wall contacts")], "contacts [count]")

    ax = axes[1, 0]
    ax.plot(t, 100 * c["max_overlap_per_radius"], color="C3", label="largest overlap")
    ax.set_ylabel("largest overlap [% of the radius]")
    ax.set_xlabel("simulated time [s]")
    ax.set_title("Overlap and bonds")
    if np.nanmax(c["bonds"]) > 0 or np.nanmax(np.nan_to_num(c["bonds_broken"])) > 0:
        counts_beside(ax, t, [(c["bonds"], "C4", "--", "intact bonds"),
                              (c["bonds_broken"], "C5", ":", "bonds broken in the stage")], "bonds [count]")
    else:
        ax.legend(fontsize=8)

    ax = axes[1, 1]
    walls = [name for name in c if name.startswith("force_") and name.endswith("_N")]
    for name in walls:
        ax.plot(t, c[name], label=name[len("force_"):-len("_N")])
    ax.set_ylabel("force on the wall, magnitude [N]")
    ax.set_xlabel("simulated time [s]")
    ax.set_title("Walls")
    if walls:
        ax.legend(fontsize=8, ncol=2)

    save_log_figure(fig, csv_path, c, png_path, f", time step {c['dt_s'][-1]:.3g} s")


if __name__ == "__main__":
    plot_main("plot_health.py", "health", main)
