#!/usr/bin/python3
"""Error against cost for the liquid validation cases, and their failure boundary.

For each case (hydrostatic_2d, dam_break_2d, poiseuille_2d) runs the grainflow CLI while one knob moves:
  resolution  l0 over three values, dt scaled with l0 (fixed CFL or diffusion number);
  time step   dt at the scene's l0, up to and past the point where a stability detector stops the run
              (run.allow_unstable_dt = true lets the load check through; the run-time detectors still apply).
Writes studies/seed003/results/sweep.csv (case, knob, l0, dt, cfl, diffusion, status, wall_seconds, particle_steps_per_s,
error, failure) for studies/seed003/plot_sweeps.py. Runs are sequential (the machine is shared).

usage: sweep.py [--binary build/grainflow] [--cases hydrostatic_2d,dam_break_2d,poiseuille_2d] [--out CSV]
(3D cases: --cases hydrostatic_3d,dam_break_3d --out studies/seed003/results/sweep_3d.csv; the 3D resolutions are coarser)
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
import front_error  # noqa: E402


def series(run):
    return front_error.series_rows(run)


def hydrostatic_error(run, l0):
    rows = [r for r in series(run) if float(r["time"]) >= 0.5]
    p = sum(float(r["bottom_pressure"]) for r in rows) / len(rows)
    return abs(p / (1000 * 9.81 * 0.1) - 1)


def dam_break_error(run, l0):
    pts = front_error.errors(run).get("koshizuka_oka_1996", [])
    return sum(abs(o - z) / z for _, z, o in pts) / len(pts)


def startup(y, t, f=0.08, nu=1e-4, L=0.01):
    u = f / (2 * nu) * y * (L - y)
    for n in range(1, 400, 2):
        u -= 4 * f * L * L / (nu * math.pi ** 3 * n ** 3) * math.sin(n * math.pi * y / L) * math.exp(
            -n * n * math.pi ** 2 * nu * t / L ** 2)
    return u


def poiseuille_error(run, l0):
    # Against the face-to-face width L: the error a user sees, wall offset included.
    worst = 0
    for r in series(run):
        t = float(r["time"])
        if t < 0.1:
            continue
        ref = 0.5 * (startup(0.005 - 0.5 * l0, t) + startup(0.005 + 0.5 * l0, t))
        worst = max(worst, abs(float(r["centre_velocity"]) - ref) / ref)
    return worst


CASES = {
    # scene, duration (s), error, (l0, dt) for resolution, dt values at the scene's l0
    "hydrostatic_2d": ("hydrostatic_2d.toml", 1.0, hydrostatic_error,
                       [(0.01, 1e-3), (0.005, 1e-3), (0.0025, 5e-4)],
                       [5e-4, 1e-3, 1.5e-3, 2e-3, 3e-3, 4e-3]),
    "dam_break_2d": ("dam_break_2d.toml", 0.25, dam_break_error,
                     [(0.0146, 1e-3), (0.0073, 5e-4), (0.00365, 2.5e-4)],
                     [2.5e-4, 5e-4, 1e-3, 1.5e-3, 2e-3, 3e-3]),
    "hydrostatic_3d": ("hydrostatic_3d.toml", 1.0, hydrostatic_error,
                       [(0.0125, 5e-4), (0.01, 5e-4), (0.1 / 14, 2.5e-4)],
                       [2.5e-4, 5e-4, 1e-3, 2e-3, 3e-3]),
    "dam_break_3d": ("dam_break_3d.toml", 0.25, dam_break_error,
                     [(0.0292, 2e-3), (0.0146, 1e-3), (0.146 / 15, 6.5e-4)],
                     [5e-4, 1e-3, 1.5e-3, 2e-3, 3e-3]),
    "poiseuille_2d": ("poiseuille_2d.toml", 0.5, poiseuille_error,
                      [(1e-3, 1e-3), (5e-4, 2.5e-4), (3.3333333333333335e-4, 1.1111111111111112e-4)],
                      [2.5e-4, 5e-4, 1e-3, 1.5e-3, 2e-3]),
}


def run_one(binary, scene, duration, l0, dt, out):
    sets = [f"liquid.l0={l0!r}", f"run.dt={dt!r}", f"run.duration={duration!r}", "run.allow_unstable_dt=true",
            f"output.series_interval={max(dt, 0.005)!r}"]
    cmd = [binary, "run", os.path.join(ROOT, "scenes", "liquid", scene), "--quiet", "--out", out]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
    return front_error._outputs().Run(out).summary


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "grainflow"))
    ap.add_argument("--cases", default="hydrostatic_2d,dam_break_2d,poiseuille_2d")
    ap.add_argument("--out", default=os.path.join(ROOT, "studies", "seed003", "results", "sweep.csv"))
    args = ap.parse_args()
    rows = []
    for name in args.cases.split(","):
        scene, duration, err, res, dts = CASES[name]
        base_l0 = res[1][0]
        jobs = [("resolution", l0, dt) for l0, dt in res] + [("time_step", base_l0, dt) for dt in dts]
        for knob, l0, dt in jobs:
            with tempfile.TemporaryDirectory() as tmp:
                s = run_one(args.binary, scene, duration, l0, dt, tmp)
                ok = s["status"] == "completed"
                e = err(tmp, l0) if ok else float("nan")
            row = {"case": name, "knob": knob, "l0": l0, "dt": dt, "cfl": s["cfl_at_load"],
                   "diffusion": s["diffusion_number"], "status": s["status"], "wall_seconds": s["wall_seconds"],
                   "particle_steps_per_s": s["particle_steps_per_second"], "error": e,
                   "failure": s.get("failure", "").split(" at t")[0]}
            rows.append(row)
            print(f"{name:15s} {knob:10s} l0={l0:.4g} dt={dt:.3g} cfl={row['cfl']:.3f} {s['status']:9s} "
                  f"wall={s['wall_seconds']:.1f}s error={e:.4f} {row['failure']}", flush=True)
    with open(args.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
