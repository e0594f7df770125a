#!/usr/bin/env python3
"""How the sampling of the seed-004 layers changes Vc: the same representative-volume run of design 1
(from its steady state, scenes/mixer_seed004_design1_steady.toml, 100 s), its layers sampled four
ways. The analysis does not act on the grains, so the four runs step the same grains and differ only
in layers.csv:

  pool40_cell50   the study's sampling: 40 samples 0.5 s apart pooled per row, cells of 50 mm
  pool1_cell50    one instant per row (as a photograph of the mixer), cells of 50 mm, any cell with a grain
  pool40_cell25   40 samples pooled, cells of 25 mm
  pool200_cell50  the whole 100 s pooled in one row, cells of 50 mm

For each, and each layer, Vc's median and range over the rows, the mean grain visits per cell, and
the Vc a random mixture of those visits gives, sqrt((1 - c) / (c n)) (the binomial spread of n draws
with key fraction c), to set the measured Vc against.

  vc_sampling.py run [--binary build/grainflow] [--runs runs/seed004_sampling]
  vc_sampling.py report [--runs runs/seed004_sampling] [--out studies/seed004/results/vc_sampling.json]
"""
import argparse
import json
import math
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))

SCENE = ROOT / "scenes" / "mixer_seed004_design1_steady.toml"
QUIET = ["--set", "output.frame_interval=0", "--set", "output.checkpoint_interval=0",
         "--set", "output.picture_interval=0", "--quiet", "--overwrite"]
VARIANTS = {
    "pool40_cell50": [],
    "pool1_cell50": ["--set", "analysis.layers.pool=1", "--set", "analysis.layers.min_grains=1"],
    "pool40_cell25": ["--set", "analysis.layers.cell=0.025"],
    "pool200_cell50": ["--set", "analysis.layers.pool=200"],
}


def median(v):
    s = sorted(v)
    n = len(s)
    return s[n // 2] if n % 2 else 0.5 * (s[n // 2 - 1] + s[n // 2])


def run(args):
    for name, extra in VARIANTS.items():
        out = pathlib.Path(args.runs) / name
        subprocess.run([args.binary, "run", str(SCENE), "--out", str(out)] + QUIET + extra, check=True)


def layer_rows(path):
    from grainflow.outputs import read_csv, rows_of
    return rows_of(read_csv(path))


def report(args):
    result = {"scene": str(SCENE.relative_to(ROOT)), "command": "studies/seed004/vc_sampling.py run && "
              "studies/seed004/vc_sampling.py report", "variants": {}}
    for name in VARIANTS:
        folder = pathlib.Path(args.runs) / name
        summary = json.loads((folder / "summary.json").read_text())
        result.setdefault("commit", summary.get("commit"))
        rows = [r for r in layer_rows(folder / "layers.csv") if math.isfinite(r["vc"])]
        layers = []
        for d in sorted({r["distance"] for r in rows}):
            at = [r for r in rows if r["distance"] == d]
            visits = [r["grains"] / r["cells"] for r in at]
            random = [math.sqrt((1 - r["fraction_a"]) / (r["fraction_a"] * r["grains"] / r["cells"]))
                      for r in at if 0 < r["fraction_a"] < 1]
            vc = [r["vc"] for r in at]
            rnd = median(random) if random else None
            # What is left of the median once a random mixture's spread is taken out (in quadrature).
            left = math.sqrt(max(0.0, median(vc) ** 2 - rnd ** 2)) if rnd is not None else None
            layers.append({"distance": d, "rows": len(at), "vc_median": median(vc), "vc_min": min(vc),
                           "vc_max": max(vc), "visits_per_cell": median(visits),
                           "random_vc_median": rnd, "vc_beyond_random": left})
        result["variants"][name] = layers
    pathlib.Path(args.out).write_text(json.dumps(result, indent=1) + "\n")
    for name, layers in result["variants"].items():
        print(name)
        for l in layers:
            rnd, left = l["random_vc_median"], l["vc_beyond_random"]
            print(f"  L {l['distance']:.3f} m: Vc {100 * l['vc_median']:5.1f} % "
                  f"({100 * l['vc_min']:.1f}-{100 * l['vc_max']:.1f}, {l['rows']} rows), "
                  f"{l['visits_per_cell']:.1f} visits a cell, random mixture "
                  + ("-" if rnd is None else f"{100 * rnd:.1f} %, beyond it {100 * left:.1f} %"))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run")
    r.add_argument("--binary", default=str(ROOT / "build" / "grainflow"))
    r.add_argument("--runs", default=str(ROOT / "runs" / "seed004_sampling"))
    r.set_defaults(func=run)
    s = sub.add_parser("report")
    s.add_argument("--runs", default=str(ROOT / "runs" / "seed004_sampling"))
    s.add_argument("--out", default=str(ROOT / "studies" / "seed004" / "results" / "vc_sampling.json"))
    s.set_defaults(func=report)
    args = p.parse_args()
    args.func(args)


if __name__ == "__main__":
    main()
