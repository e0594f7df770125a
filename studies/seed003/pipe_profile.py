#!/usr/bin/python3
"""The transport pipe's liquid alone: scenes/liquid/transport_pipe.toml without its grains, driven as the
study drives it, and the axial velocity profile it settles on, beside the profiles of the runs with grains.
It tells apart the two candidate causes of the study's centre running slower than its mean: the liquid's
own flow (walls, drive, resolution) or the grains' drag on it.

  /usr/bin/python3 studies/seed003/pipe_profile.py run [--speeds 2 5] [--duration 1.5] [--from 1.0]
                                                   [--binary build/grainflow] [--threads 2]
      one liquid-only case per speed into runs/liquid/pipe_profile/u<U>, each frame reduced to ring
      profiles (studies/seed003/transport_pipe.py's rings of r/R 0.1), written with the cases with grains
      from studies/seed003/results/transport_pipe.json to studies/seed003/results/pipe_profile.json
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "python"))
import transport_pipe as tp  # noqa: E402
from grainflow.vtp import read_vtp  # noqa: E402

OUT = "studies/seed003/results/pipe_profile.json"
LIQUID_SECTIONS = ("run", "liquid", "geometry", "fluid", "drive", "output")


def liquid_only(text):
    """The scene's liquid sections ([run] without the grains' skin), its grains' sections dropped."""
    keep, out = False, []
    for line in text.splitlines():
        head = re.match(r"^\[\[?([a-z_.]+)\]\]?", line)
        if head:
            keep = head.group(1) in LIQUID_SECTIONS
        if keep and not line.startswith("skin"):
            out.append(line)
    return "\n".join(out) + "\n"


def profile(run_dir, t_from):
    """The fluid nodes' mean axial velocity per ring, pooled over the frames from t_from on, and the frames."""
    count, total, used = [0] * tp.RINGS, [0.0] * tp.RINGS, 0
    for t, path in tp.frames(run_dir, "."):
        if t < t_from - 1e-9:
            continue
        used += 1
        liq = read_vtp(path)
        for (_, y, z), (u, _, _), kind in zip(liq["Points"], liq["velocity"], tp.node_kinds(liq)):
            if kind == tp.FLUID:
                k = tp.ring(math.hypot(y, z))
                count[k] += 1
                total[k] += u
    return [s / c if c else None for s, c in zip(total, count)], used


def centre_over_mean(u, counts_weighted=None):
    """The innermost ring's speed over the area-weighted mean of the rings (the flux over the area)."""
    area = [(k + 1) ** 2 - k ** 2 for k in range(tp.RINGS)]
    mean = sum(a * v for a, v in zip(area, u)) / sum(area)
    return u[0] / mean, mean


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("command", choices=["run"])
    p.add_argument("--speeds", type=float, nargs="*", default=[2.0, 5.0])
    p.add_argument("--duration", type=float, default=1.5)
    p.add_argument("--from", dest="from_s", type=float, default=1.0)
    p.add_argument("--binary", default="build/grainflow")
    p.add_argument("--threads", type=int, default=2)
    a = p.parse_args()
    scene = liquid_only(open(os.path.join(ROOT, tp.SCENE)).read())
    with_grains = json.load(open(os.path.join(ROOT, tp.DOCS)))["runs"]
    result = {"command": "studies/seed003/pipe_profile.py run " + " ".join(sys.argv[2:]), "scene": tp.SCENE,
              "from_s": a.from_s, "duration_s": a.duration, "rings": [(k + 0.5) / tp.RINGS for k in range(tp.RINGS)],
              "cases": {}}
    for u in a.speeds:
        name = f"u{u:g}"
        folder = os.path.join(ROOT, "runs/liquid/pipe_profile", name)
        os.makedirs(folder, exist_ok=True)
        path = os.path.join(folder, "scene.toml")
        open(path, "w").write(scene)
        subprocess.run([a.binary, "run", path, "--out", folder, "--threads", str(a.threads), "--set",
                        f"drive.mean_velocity={u}", "--set", f"run.velocity_scale={1.2 * u}", "--set",
                        f"run.duration={a.duration}"], check=True, cwd=ROOT)
        prof, used = profile(folder, a.from_s)
        ratio, mean = centre_over_mean(prof)
        summary = json.load(open(os.path.join(folder, "summary.json")))
        case = {"frames": used, "u_profile": prof, "centre_over_mean": ratio, "ring_mean": mean,
                "wall_seconds": summary.get("wall_seconds")}
        g = with_grains.get(name)
        if g:
            gr, _ = centre_over_mean(g["u_profile"])
            case["with_grains"] = {"u_profile": g["u_profile"], "centre_over_mean": gr, "from_s": g["from_s"],
                                   "to_s": g["to_s"]}
        result["cases"][name] = case
        print(name, "liquid alone: centre/mean %.3f" % ratio,
              ("with grains: %.3f" % case["with_grains"]["centre_over_mean"]) if g else "")
    with open(os.path.join(ROOT, OUT), "w") as fh:
        json.dump(result, fh, indent=1)


if __name__ == "__main__":
    main()
