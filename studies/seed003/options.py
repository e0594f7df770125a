#!/usr/bin/python3
"""Measures the optional terms against pressure noise and clustering, one at a time, on the 2D hydrostatic tank
and the 2D dam break (defaults: seed gradient "sum", clip_negative on, no compressibility, collision model at
0.8 l0, gamma 0.001). Writes studies/seed003/results/options.csv: case, option, status, error, pressure RMS (tank), wall time.

usage: options.py [--binary build-liquid/grainflow]
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
import sweep  # noqa: E402

VARIANTS = [
    ("default", []),
    ("gradient = min", ["liquid.gradient=\"min\""]),
    ("clip_negative = false", ["liquid.clip_negative=false"]),
    ("compressibility = 1e-8 1/Pa", ["liquid.compressibility=1e-8"]),
    ("collision off", ["liquid.collision_distance=0"]),
    ("gamma = 0.01", ["liquid.gamma=0.01"]),
    ("re = 3.1 l0", ["liquid.re=3.1"]),
]
CASES = [("hydrostatic_2d", "hydrostatic_2d.toml", 2.0), ("dam_break_2d", "dam_break_2d.toml", 0.25)]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--binary", default=os.path.join(ROOT, "build-liquid", "grainflow"))
    args = ap.parse_args()
    rows = []
    for case, scene, duration in CASES:
        for name, sets in VARIANTS:
            with tempfile.TemporaryDirectory() as tmp:
                cmd = [args.binary, "run", os.path.join(ROOT, "scenes", "liquid", scene), "--quiet", "--out", tmp,
                       "--set", f"run.duration={duration}"]
                for s in sets:
                    cmd += ["--set", s]
                subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
                s = sweep.front_error._outputs().Run(tmp).summary
                ok = s["status"] == "completed"
                rms = float("nan")
                if case == "hydrostatic_2d" and ok:
                    ps = [float(r["bottom_pressure"]) for r in sweep.series(tmp) if float(r["time"]) >= 1.0]
                    m = sum(ps) / len(ps)
                    rms = (sum((p - m) ** 2 for p in ps) / len(ps)) ** 0.5
                    err = m / 981.0 - 1
                elif ok:
                    pts = sweep.front_error.errors(tmp)["koshizuka_oka_1996"]
                    err = sum((o - z) / z for _, z, o in pts) / len(pts)
                else:
                    err = float("nan")
            row = {"case": case, "option": name, "status": s["status"], "error": err, "pressure_rms_pa": rms,
                   "wall_seconds": s["wall_seconds"], "failure": s.get("failure", "").split(" at t")[0]}
            rows.append(row)
            print(row, flush=True)
    with open(os.path.join(ROOT, "studies", "seed003", "results", "options.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
