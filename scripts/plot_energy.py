#!/usr/bin/env python3
"""Plot run-stage's energy log (OUT.energy.csv) to PNG: what the particles and contacts hold and
what has been dissipated and released, stacked against simulated time, with the energy the balance
says they must add up to (what was held at the start, plus the work put in, less the potential
energy gained), and below it the balance error (docs/physics.md eq. P38-P39)."""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from plot_health import read_health  # noqa: E402
from post_table import save_atomically  # noqa: E402

# The stacked terms: (column, label), held first, then lost.
STACK = [("kinetic_translation_J", "kinetic, translation"), ("kinetic_rotation_J", "kinetic, rotation"),
         ("elastic_normal_J", "elastic, normal (bonds too)"), ("elastic_tangential_J", "elastic, tangential springs"),
         ("damping_normal_J", "dissipated: normal dashpot"), ("friction_J", "dissipated: friction, tangential dashpot"),
         ("global_damping_J", "dissipated: global damping"), ("bonds_released_J", "released by broken bonds")]


def main(csv_path: str, png_path: str) -> None:
    c = read_health(csv_path)
    t = c["time_s"]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(9, 7), dpi=110, sharex=True, gridspec_kw={"height_ratios": [3, 1]})
    top.stackplot(t, *[c[k] for k, _ in STACK], labels=[label for _, label in STACK], alpha=0.8)
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
    steps = c["step"]
    fig.suptitle(f"{csv_path}: steps {int(steps[0])} to {int(steps[-1])}", fontsize=9)
    save_atomically(fig, png_path)
    plt.close(fig)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: plot_energy.py RUN.energy.csv OUT.png")
    main(sys.argv[1], sys.argv[2])
