#!/usr/bin/env python3
"""Plot run-stage's energy log (OUT.energy.csv) to PNG: what the particles, contacts and fibres
hold and what has been dissipated and released, stacked against simulated time, with the energy
the balance says they must add up to (what was held at the start, plus the work put in and the
energy of inserted particles, less the potential energy gained), and below it the balance error
(docs/physics.md eq. P38-P45). Terms that stay zero in the run are left out of the legend."""
import numpy as np
from run_log_figure import log_figure, plot_main, read_columns, save_log_figure

# The stacked terms: (column, label), held first, then lost.
STACK = [("kinetic_translation_J", "kinetic, translation"), ("kinetic_rotation_J", "kinetic, rotation"),
         ("elastic_normal_J", "elastic, normal (bonds too)"), ("elastic_tangential_J", "elastic, tangential springs"),
         ("elastic_rolling_J", "elastic, rolling springs"), ("elastic_fibres_J", "elastic, fibres"),
         ("damping_normal_J", "dissipated: normal dashpot"), ("friction_J", "dissipated: friction, tangential dashpot"),
         ("global_damping_J", "dissipated: global damping"), ("rolling_J", "dissipated: rolling resistance"),
         ("bonds_released_J", "released by broken bonds"), ("fibres_released_J", "released by broken fibres")]


def main(csv_path: str, png_path: str) -> None:
    c = read_columns(csv_path)
    t = c["time_s"]
    fig, (top, bottom) = log_figure(2, 1, (9, 7), height_ratios=[3, 1])
    shown = [(k, label) for k, label in STACK if np.any(c[k] != 0)]
    top.stackplot(t, *[c[k] for k, _ in shown], labels=[label for _, label in shown], alpha=0.8)
    # What the stack must reach: the kinetic and elastic energy at the ledger's reference, plus the
    # work put in, less the potential energy gained since; the stack less the balance error.
    budget = sum(c[k] for k, _ in STACK) - c["balance_error_J"]
    top.plot(t, budget, color="k", lw=1.5, label="held at the start + work in − potential gained")
    top.set_ylabel("energy [J]")
    top.set_title("Energy held, dissipated and released")
    top.legend(fontsize=7, loc="upper left", ncol=2)

    bottom.plot(t, 100 * c["balance_error_relative"], color="C3")
    bottom.axhline(0, color="k", lw=0.5)
    bottom.set_ylabel("balance error [% of scale]")
    bottom.set_xlabel("simulated time [s]")
    save_log_figure(fig, csv_path, c, png_path)


if __name__ == "__main__":
    plot_main("plot_energy.py", "energy", main)
