#!/usr/bin/python3
"""Dam-break surge front against the experiments: Z/a against T = t sqrt(2 g / a).

usage: plot_dam_break.py OUT.png LABEL=RUN_SERIES_CSV [LABEL=RUN_SERIES_CSV ...]
Each RUN_SERIES_CSV is a run's series.csv (column surge_front, m). Experiments from
studies/seed003/results/dam_break_experiments.csv.
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import front_error  # noqa: E402

A, G = 0.146, 9.81


def main():
    out = sys.argv[1]
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for spec in sys.argv[2:]:
        label, path = spec.rsplit("=", 1)
        T, Z = front_error.front_curve(front_error._outputs().read_csv(path), A, G)
        ax.plot(T, Z, "-", label=label)
    exp = front_error.experiments()
    for src, marker, name in [("martin_moyce_a2.25in", "o", "Martin & Moyce 1952 (a = 2.25 in)"),
                              ("koshizuka_oka_1996", "s", "Koshizuka & Oka 1996 (experiment)")]:
        pts = [(t, z) for s, t, z in exp if s == src and z <= 4.2]
        ax.plot([p[0] for p in pts], [p[1] for p in pts], marker, mfc="none", color="k" if marker == "o" else "C3",
                label=name)
    ax.axhline(4.0, color="0.6", lw=0.8, ls=":")
    ax.text(0.1, 4.05, "far wall", color="0.4", fontsize=8)
    ax.set_xlabel(r"$T = t\,\sqrt{2g/a}$")
    ax.set_ylabel(r"surge front $Z/a$")
    ax.set_xlim(0, 3.6)
    ax.set_ylim(0.9, 4.3)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    ax.set_title("2D/3D dam break (a = 0.146 m, column 2a high) against experiments", fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=130)


if __name__ == "__main__":
    main()
