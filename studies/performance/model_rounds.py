#!/usr/bin/env python3
"""Each model's stepping rate, two builds of grainflow alternated round by round (A B A B ...).

    python3 studies/performance/model_rounds.py BEFORE_DIR AFTER_DIR OUT.json [--rounds 5]

BEFORE_DIR and AFTER_DIR hold a build's grainflow and grainflow_mpi. One scene a model (spheres,
composite bodies, liquid, liquid with grains, spheres on two MPI ranks), each on one thread a rank and
a fixed number of main-stage steps; the rate is the one its summary.json reports for the main stage
(particle-steps/s; body-steps/s for bodies; liquid steps/s for the coupled run, whose particle rate
builds before the run skeleton did not report). OUT.json holds every round's rates and, per model, the after/before ratios' median
and range.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "python"))


def _outputs():
    """grainflow.outputs, imported where run files are read: it needs numpy, the tables do not."""
    import grainflow.outputs
    return grainflow.outputs


MODELS = [
    ("spheres", ["scenes/drum_quick.toml", "--steps", "25000"], False),
    ("bodies", ["scenes/hopper_seed002_cost.toml", "--steps", "2000"], False),
    ("liquid", ["scenes/liquid/dam_break_3d.toml", "--steps", "300"], False),
    ("coupled", ["scenes/liquid/fluidised_bed.toml", "--steps", "100"], False),
    ("spheres on 2 ranks", ["scenes/drum_quick.toml", "--steps", "25000"], True),
]


def rate(summary):
    if summary.get("model") == "coupled":
        return summary["steps_this_run"] / summary["wall_seconds"]
    for key in ("body_steps_per_second", "particle_steps_per_second"):
        if summary.get(key):
            return summary[key]
    return summary["steps_this_run"] / summary["wall_seconds"]


def run(build, args, ranks, out):
    scene = os.path.join(ROOT, args[0])
    if ranks:
        cmd = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-n", "2", os.path.join(build, "grainflow_mpi"),
               "run", scene, *args[1:], "--threads", "1", "--out", out]
    else:
        cmd = [os.path.join(build, "grainflow"), "run", scene, *args[1:], "--threads", "1", "--quiet", "--out", out]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=ROOT)
    return rate(_outputs().Run(out).summary)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("before")
    ap.add_argument("after")
    ap.add_argument("out")
    ap.add_argument("--rounds", type=int, default=5)
    a = ap.parse_args()
    result = {"command": "python3 studies/performance/model_rounds.py BEFORE AFTER OUT --rounds %d" % a.rounds,
              "threads_per_rank": 1, "models": {}}
    with tempfile.TemporaryDirectory() as tmp:
        for name, args, ranks in MODELS:
            rows = []
            for k in range(a.rounds):
                b = run(a.before, args, ranks, os.path.join(tmp, "before"))
                f = run(a.after, args, ranks, os.path.join(tmp, "after"))
                rows.append({"round": k + 1, "before": b, "after": f, "ratio": f / b})
                print(f"{name}: round {k + 1}: before {b:.4g}, after {f:.4g}, ratio {f / b:.3f}", flush=True)
            ratios = sorted(r["ratio"] for r in rows)
            result["models"][name] = {"scene": args[0], "steps": int(args[2]), "rounds": rows,
                                      "ratio_median": statistics.median(ratios),
                                      "ratio_min": ratios[0], "ratio_max": ratios[-1]}
    with open(a.out, "w") as f:
        json.dump(result, f, indent=1)
        f.write("\n")
    for name, m in result["models"].items():
        print(f"{name}: after/before median {m['ratio_median']:.3f} ({m['ratio_min']:.3f}-{m['ratio_max']:.3f})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
