#!/usr/bin/python3
"""One model term changed at a time on seed 003's developed pipe flow: each branch resumes the finished 105-s case
at 2 m/s (runs/liquid/transport_pipe/u2_long, which `transport_pipe.py run --speeds 2 --tag long --duration 105
--courant 0.2 --frame-interval 0.1 --prune --threads 2 --set output.series_interval=0.05` writes) from its last
checkpoint, with that case's own settings and one change, to END; statistics from START + SETTLE to END
(transport_pipe.py's frames.csv rows and measure()). A branch stopped short of END goes on from its own
checkpoint. spin_candidates.py measures the same terms over the first 2 s from rest, where the liquid has not
yet developed its pipe profile; these branches measure them where the 100-s statistics are taken.

  /usr/bin/python3 studies/seed003/developed_branches.py run [--only NAME ...] [--threads 1]
      each branch into runs/liquid/developed_branches/<name> (one after another), then collect
  /usr/bin/python3 studies/seed003/developed_branches.py collect
      studies/seed003/results/developed_branches.json: per branch its overrides, mean |omega|, var(r/R) with
      the frames' spread, the volume-fraction profile and peak, the grains' mean axial speed, the liquid's
      profile and its centre over U; rows of branches whose folders are gone are kept
  /usr/bin/python3 studies/seed003/developed_branches.py table [studies/seed003/results/developed_branches.json]
      the results page's table (tools/readme/tables.py calls it; needs no numpy)
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "python"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import transport_pipe as tp  # noqa: E402

SPEED, START, SETTLE, END = 2.0, 105.0, 4.0, 115.0
BASE = os.path.join(ROOT, tp.RUNS, "u2_long")
RUNS = os.path.join(ROOT, "runs/liquid/developed_branches")
OUT = os.path.join(ROOT, "studies/seed003/results/developed_branches.json")
BRANCHES = {
    "unchanged": [],
    "shear_lift": ['coupling.shear_lift="saffman_mei"'],
    "grains_frictionless": ["contact.friction=0.0", "contact.wall={friction=0.2}"],
    "rotational_drag": ['coupling.rotational_drag="dennis"'],
    "wall_frictionless": ["contact.wall={friction=0.0}"],
    "shear_lift_rotational_drag": ['coupling.shear_lift="saffman_mei"', 'coupling.rotational_drag="dennis"'],
}
LABELS = {
    "unchanged": "the 105-s case continued unchanged",
    "shear_lift": "shear lift (Saffman-Mei)",
    "grains_frictionless": "no grain-grain friction (wall 0.2)",
    "rotational_drag": "liquid torque (rotational drag, Dennis et al.)",
    "wall_frictionless": "no grain-wall friction",
    "shear_lift_rotational_drag": "shear lift and liquid torque",
}


def base_overrides():
    """The long case's own --set list, its duration replaced by END."""
    sets = json.load(open(os.path.join(BASE, "summary.json")))["overrides"]
    return [s for s in sets if not s.startswith("run.duration=")] + [f"run.duration={END}"]


def reached(folder):
    """The simulated time a branch's folder has reached (0 without one)."""
    path = os.path.join(folder, "summary.json")
    if not os.path.exists(path):
        return 0.0
    return json.load(open(path)).get("simulated_time") or 0.0


def run_one(name, binary, threads):
    """A branch from the long case's checkpoint, or one that stopped short of END continued from its own."""
    folder = os.path.join(RUNS, name)
    if not START < reached(folder) < END - 1e-6:
        shutil.rmtree(folder, ignore_errors=True)
        shutil.copytree(BASE, folder)
    cmd = [binary, "run", os.path.join(ROOT, tp.SCENE), "--out", folder, "--threads", str(threads), "--quiet",
           "--resume", os.path.join(folder, "checkpoints", "checkpoint.gfc")]
    for s in base_overrides() + BRANCHES[name]:
        cmd += ["--set", s]
    with open(os.path.join(RUNS, name + ".log"), "w") as log:
        rc = subprocess.call(cmd, stdout=log, stderr=subprocess.STDOUT)
    tp.update_frames(folder)
    return rc


def collect():
    out = {"speed_m_s": SPEED, "branch_from_s": START, "statistics_s": [START + SETTLE, END], "scene": tp.SCENE,
           "seed_2_m_s": dict(zip(("r_variance", "phi_peak_r", "phi_peak_percent", "spin"), tp.SEED[2])),
           "branches": {}}
    kept = json.load(open(OUT))["branches"] if os.path.exists(OUT) else {}
    for name, sets in BRANCHES.items():
        folder = os.path.join(RUNS, name)
        m = tp.measure(folder, START + SETTLE, END) if os.path.isdir(folder) else None
        if m is None or m.get("to_s") is None or m["to_s"] < END - 1e-6:
            if name in kept:
                out["branches"][name] = kept[name]
            continue
        out["branches"][name] = {"overrides": sets, **{k: m[k] for k in (
            "frames", "from_s", "to_s", "spin", "r_variance", "r_variance_frame_sd", "phi_peak_r", "phi_peak",
            "grain_speed", "rings", "phi_profile", "u_profile")},
            "centre_liquid_over_U": m["u_profile"][0] / SPEED,
            "spin_per_frame": [[round(r["time"], 3), round(r["spin"], 3)]
                               for r in tp.read_rows(os.path.join(folder, "frames.csv")) if r["time"] >= START - 1e-9]}
    with open(OUT, "w") as fh:
        json.dump(out, fh, indent=1)
        fh.write("\n")
    for name, b in out["branches"].items():
        print(name, {k: b[k] for k in ("spin", "r_variance", "phi_peak_r", "grain_speed", "centre_liquid_over_U")})


def table(path):
    data = json.load(open(path))
    a, b = data["statistics_s"]
    print(f"| branch from {data['branch_from_s']:g} s, statistics {a:g}–{b:g} s | mean spin (rad/s) "
          "| var(r/R) (frames' sd) | peak r/R (%) | volume fraction at r/R 0.8–0.9 (%) | grains' mean speed (m/s) "
          "| centre liquid / U |")
    print("|---|---|---|---|---|---|---|")
    for name, c in data["branches"].items():
        print(f"| {LABELS.get(name, name)} | {c['spin']:.2f} | {c['r_variance']:.4f} (± {c['r_variance_frame_sd']:.4f}) "
              f"| {c['phi_peak_r']:.2f} ({c['phi_peak']:.1f}) | {c['phi_profile'][8]:.1f} | {c['grain_speed']:.2f} "
              f"| {c['centre_liquid_over_U']:.3f} |")
    var, pr, pp, spin = tp.SEED[2]
    print(f"| the paper, 2 m/s | {spin:.2f} | {var:.4f} | {pr:.2f} ({pp:.1f}) | — | — | above 1 |")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("command", choices=["run", "collect", "table"])
    p.add_argument("path", nargs="?", default=OUT)
    p.add_argument("--only", nargs="*", default=None)
    p.add_argument("--threads", type=int, default=1)
    p.add_argument("--binary", default=os.path.join(ROOT, "build/grainflow"))
    a = p.parse_args()
    if a.command == "table":
        table(a.path)
        return
    if a.command == "run":
        if not os.path.exists(os.path.join(BASE, "checkpoints", "checkpoint.gfc")):
            sys.exit(f"{BASE}: no checkpoint; run the 105-s case first (see this script's help)")
        os.makedirs(RUNS, exist_ok=True)
        for name in a.only or list(BRANCHES):
            print(f"{name}: exit {run_one(name, a.binary, a.threads)}", flush=True)
    collect()


if __name__ == "__main__":
    main()
