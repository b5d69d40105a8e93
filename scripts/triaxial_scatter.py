#!/usr/bin/env python3
"""How a triaxial test's strength and the fibres' gain spread with the packing: for several fills
(each sheared without and with fibres, from the same consolidated sample), the peak and residual
deviator stress and friction angles of each (scripts/triaxial_report.py, docs/physics.md eq. P66),
the gains in peak and residual strength, and their mean, standard deviation and range over the fills.

usage: triaxial_scatter.py --fill SEED:WALLS_0.csv:WALLS_FIBRES.csv ... --fibre-fraction F
                           --table T.csv --png P.png
"""
import argparse
import sys

from debian_python import ensure  # noqa: E402

ensure("numpy", "matplotlib")

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from post_table import save_atomically, write_csv  # noqa: E402
from triaxial_report import history, summarise  # noqa: E402

COLUMNS = ["q_peak_0_Pa", "phi_peak_0_deg", "q_residual_0_Pa", "phi_residual_0_deg",
           "q_peak_fibres_Pa", "phi_peak_fibres_deg", "q_residual_fibres_Pa", "phi_residual_fibres_deg", "gain_peak", "gain_residual"]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fill", action="append", required=True, help="SEED:WALLS_0.csv:WALLS_FIBRES.csv (run-stage --wall-forces logs)")
    ap.add_argument("--fibre-fraction", type=float, required=True, help="of the reinforced runs (0.01 for 1 %%): the plot's label")
    ap.add_argument("--box", default="box", help="the box wall's name (faces BOX.xmin ... BOX.zmax)")
    ap.add_argument("--table", required=True)
    ap.add_argument("--png", required=True)
    a = ap.parse_args()

    seeds, values = [], []
    for spec in a.fill:
        parts = spec.split(":")
        if len(parts) != 3:
            sys.exit(f"--fill {spec}: expected SEED:WALLS_0.csv:WALLS_FIBRES.csv")
        bare, reinforced = (summarise(history(p, a.box)) for p in parts[1:])
        seeds.append(parts[0])
        values.append([bare["q_peak"], bare["phi_peak"], bare["q_res"], bare["phi_res"],
                       reinforced["q_peak"], reinforced["phi_peak"], reinforced["q_res"], reinforced["phi_res"],
                       reinforced["q_peak"] / bare["q_peak"] - 1, reinforced["q_res"] / bare["q_res"] - 1])
    v = np.array(values)
    stats = {"mean": v.mean(axis=0), "sd": v.std(axis=0, ddof=1) if len(v) > 1 else np.full(v.shape[1], np.nan),
             "min": v.min(axis=0), "max": v.max(axis=0)}
    write_csv(a.table, ["fill_seed", *COLUMNS], [[s, *row] for s, row in zip(seeds, values)] + [[k, *row] for k, row in stats.items()])
    col = {c: k for k, c in enumerate(COLUMNS)}
    for name, text in (("q_peak_0_Pa", "peak q without fibres"), ("q_peak_fibres_Pa", "peak q with fibres"),
                       ("gain_peak", "gain in peak q"), ("gain_residual", "gain in residual q")):
        k = col[name]
        scale, unit = (1e-3, " kPa") if name.endswith("_Pa") else (100, " %")
        print(f"{text}: mean {scale * stats['mean'][k]:.1f}{unit}, sd {scale * stats['sd'][k]:.1f}, "
              f"range {scale * stats['min'][k]:.1f} to {scale * stats['max'][k]:.1f} over {len(seeds)} fills")

    label = f"{100 * a.fibre_fraction:g} % fibres"
    fig, (ax_q, ax_g) = plt.subplots(1, 2, figsize=(11, 4.5), dpi=110)
    x = np.arange(len(seeds))
    for name, marker, color, text in (("0", "o", "C0", "no fibres"), ("fibres", "s", "C2", label)):
        ax_q.plot(x, v[:, col[f"q_peak_{name}_Pa"]] / 1e3, marker, color=color, label=f"peak, {text}")
        ax_q.plot(x, v[:, col[f"q_residual_{name}_Pa"]] / 1e3, marker, color=color, mfc="none", label=f"residual, {text}")
    ax_q.set_xticks(x, seeds), ax_q.set_xlabel("fill seed"), ax_q.set_ylabel("deviator stress q [kPa]"), ax_q.legend(fontsize=8)
    ax_q.set_title("Strength of each packing")
    ax_g.plot(x, 100 * v[:, col["gain_peak"]], "o", label="peak")
    ax_g.plot(x, 100 * v[:, col["gain_residual"]], "s", mfc="none", label="residual")
    for k, ls in ((col["gain_peak"], "-"), (col["gain_residual"], "--")):
        ax_g.axhline(100 * stats["mean"][k], ls=ls, color="grey", lw=0.8)
    ax_g.set_xticks(x, seeds), ax_g.set_xlabel("fill seed"), ax_g.set_ylabel(f"gain with {label} [%]"), ax_g.legend(fontsize=8)
    ax_g.set_title("Gain of each packing (grey: the means)")
    save_atomically(fig, a.png)


if __name__ == "__main__":
    main()
