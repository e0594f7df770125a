#!/usr/bin/python3
"""Charts from studies/seed003/results/sweep.csv (studies/seed003/sweep.py): per case, error against wall time as l0 and dt
change, and the failure boundary (error, or the detector that stopped the run, against the CFL number or, for
the viscous case, the diffusion number).

usage: plot_sweeps.py [SWEEP_CSV] [OUT_DIR]   (defaults: studies/seed003/results/sweep.csv, studies/seed003/results)
Writes OUT_DIR/sweep_<case>.png.
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
ERROR_LABEL = {
    "hydrostatic_2d": "floor pressure error vs rho g H",
    "dam_break_2d": "mean |front error| vs Koshizuka-Oka",
    "poiseuille_2d": "worst centre-velocity error vs series (width L)",
    "hydrostatic_3d": "floor pressure error vs rho g H",
    "dam_break_3d": "mean |front error| vs Koshizuka-Oka",
}


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "studies", "seed003", "results", "sweep.csv")
    out_dir = sys.argv[2] if len(sys.argv) > 2 else os.path.join(ROOT, "studies", "seed003", "results")
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for case in sorted({r["case"] for r in rows}):
        rs = [r for r in rows if r["case"] == case]
        fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
        for knob, marker in [("resolution", "o-"), ("time_step", "s--")]:
            pts = [r for r in rs if r["knob"] == knob and r["status"] == "completed"]
            pts.sort(key=lambda r: float(r["wall_seconds"]))
            a1.plot([float(r["wall_seconds"]) for r in pts], [float(r["error"]) for r in pts], marker,
                    label=f"{knob.replace('_', ' ')} varies")
            for r in pts:
                txt = f"l0={float(r['l0']) * 1e3:.3g}mm" if knob == "resolution" else f"dt={float(r['dt']):.2g}"
                a1.annotate(txt, (float(r["wall_seconds"]), float(r["error"])), fontsize=7, xytext=(3, 3),
                            textcoords="offset points")
        a1.set_xscale("log")
        a1.set_yscale("log")
        a1.set_xlabel("wall time of the run (s, 2 shared cores)")
        a1.set_ylabel(ERROR_LABEL.get(case, "error"))
        a1.grid(alpha=0.3, which="both")
        a1.legend(fontsize=8)
        viscous = case.startswith("poiseuille")
        xkey = "diffusion" if viscous else "cfl"
        ts = sorted((r for r in rs if r["knob"] == "time_step"), key=lambda r: float(r[xkey]))
        ok = [r for r in ts if r["status"] == "completed"]
        bad = [r for r in ts if r["status"] != "completed"]
        a2.plot([float(r[xkey]) for r in ok], [float(r["error"]) for r in ok], "o-", label="completed")
        top = max([float(r["error"]) for r in ok] + [1e-3])
        for r in bad:
            a2.axvline(float(r[xkey]), color="C3", ls=":", lw=1)
            a2.annotate(r["failure"].split(" at t")[0], (float(r[xkey]), top), rotation=90, fontsize=7, color="C3", va="top",
                        xytext=(2, 0), textcoords="offset points")
        if bad:
            a2.plot([], [], ":", color="C3", label="stopped by a detector")
        a2.set_xlabel("diffusion number nu dt / l0^2" if viscous else "CFL number (velocity scale) dt / l0")
        a2.set_ylabel(ERROR_LABEL.get(case, "error"))
        a2.set_yscale("log")
        a2.grid(alpha=0.3, which="both")
        a2.legend(fontsize=8)
        fig.suptitle(f"{case}: error against cost, and the failure boundary", fontsize=10)
        fig.tight_layout()
        fig.savefig(os.path.join(out_dir, f"sweep_{case}.png"), dpi=120)
        plt.close(fig)


if __name__ == "__main__":
    main()
