#!/usr/bin/env python3
"""Design 1 of the seed-004 mixer with the representative-volume law, run from empty for 300 s with one
thing changed at a time, and Vc(L) of each: the median of layers.csv's pooled rows (20 s each) after
the hold-up is steady (from 150 s, as studies/seed004/mixer_report.py finds it), with the spread a
random mixture of the cells' visits gives (vc_sampling.py) beside it. Two experiments:

  segregation  is the high Vc segregation by size or density, or the way the mixture travels? The feed's
               key volume fraction 0.33 kept:
                 seed          the seed's components: the key 0.778 of the carrier's size, 0.786 of its density
                 same_size     the key as large as the carrier (22 mm), its density the seed's
                 same_density  the key as dense as the carrier (1400 kg/m^3), its size the seed's
                 identical     the key the carrier's size and density: a label only, so its Vc is what the
                               transport leaves unmixed
  reading      the law's settings the seed leaves open:
                 seed          the scene's: cut-off 1e-3, friction regularised below 0.01 m/s
                 cutoff_1e-4   the exponential tails cut at 1e-4 of their amplitude
                 slip_1e-3     friction regularised below 1 mm/s (run.dt 5e-5 s, under 0.1 of its time-step term)

  vc_variants.py run EXPERIMENT [--binary build/grainflow] [--runs runs/seed004_EXPERIMENT]
  vc_variants.py report EXPERIMENT [--runs runs/seed004_EXPERIMENT] [--out studies/seed004/results/vc_EXPERIMENT.json]
"""
import argparse
import json
import math
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))

SCENE = ROOT / "scenes" / "mixer_seed004_design1.toml"
QUIET = ["--set", "output.frame_interval=0", "--set", "output.checkpoint_interval=0",
         "--set", "output.picture_interval=0", "--quiet", "--overwrite"]
EQUAL_DENSITY_FEED = ["--set", "feed.0.fractions={ key = 0.33, carrier = 0.67 }"]  # by mass = by volume
EXPERIMENTS = {
    "segregation": {
        "seed": [],
        "same_size": ["--set", "species.1.diameter=0.022"],
        "same_density": ["--set", "species.1.density=1400"] + EQUAL_DENSITY_FEED,
        "identical": ["--set", "species.1.diameter=0.022", "--set", "species.1.density=1400"] + EQUAL_DENSITY_FEED,
    },
    "reading": {
        "seed": [],
        "cutoff_1e-4": ["--set", "contact.cutoff=1e-4"],
        "slip_1e-3": ["--set", "contact.slip_speed=0.001", "--set", "run.dt=5e-5"],
    },
}
STEADY_FROM = 150.0  # s


def median(v):
    s = sorted(v)
    n = len(s)
    return s[n // 2] if n % 2 else 0.5 * (s[n // 2 - 1] + s[n // 2])


def run(args):
    for name, extra in EXPERIMENTS[args.experiment].items():
        out = pathlib.Path(args.runs) / name
        subprocess.run([args.binary, "run", str(SCENE), "--out", str(out)] + QUIET + extra, check=True)


def report(args):
    from grainflow.outputs import read_csv, rows_of
    variants = EXPERIMENTS[args.experiment]
    result = {"scene": str(SCENE.relative_to(ROOT)), "steady_from_s": STEADY_FROM,
              "command": f"studies/seed004/vc_variants.py run {args.experiment} && "
                         f"studies/seed004/vc_variants.py report {args.experiment}",
              "variants": {n: variants[n] for n in variants}, "vc": {}}
    for name in variants:
        folder = pathlib.Path(args.runs) / name
        summary = json.loads((folder / "summary.json").read_text())
        result.setdefault("commit", summary.get("commit"))
        rows = [r for r in rows_of(read_csv(folder / "layers.csv"))
                if math.isfinite(r["vc"]) and r["time"] >= STEADY_FROM]
        layers = []
        for d in sorted({r["distance"] for r in rows}):
            at = [r for r in rows if r["distance"] == d]
            random = [math.sqrt((1 - r["fraction_a"]) / (r["fraction_a"] * r["grains"] / r["cells"]))
                      for r in at if 0 < r["fraction_a"] < 1]
            vc = [r["vc"] for r in at]
            layers.append({"distance": d, "rows": len(at), "vc_median": median(vc), "vc_min": min(vc),
                           "vc_max": max(vc), "random_vc_median": median(random) if random else None,
                           "key_fraction": median([r["fraction_a"] for r in at])})
        result["vc"][name] = layers
    pathlib.Path(args.out).write_text(json.dumps(result, indent=1) + "\n")
    names = list(variants)
    print("L (m)  " + "  ".join(f"{n:>22}" for n in names) + "   (Vc median %, random-mixture %)")
    for k, l in enumerate(result["vc"][names[0]]):
        cells = []
        for n in names:
            v = result["vc"][n][k]
            rnd = v["random_vc_median"]
            cells.append(f"{100 * v['vc_median']:5.1f} ({100 * v['vc_min']:4.1f}-{100 * v['vc_max']:4.1f}) "
                         + ("  -" if rnd is None else f"{100 * rnd:4.1f}"))
        print(f"{l['distance']:.3f}  " + "  ".join(f"{c:>22}" for c in cells))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    for command, func in (("run", run), ("report", report)):
        c = sub.add_parser(command)
        c.add_argument("experiment", choices=sorted(EXPERIMENTS))
        c.add_argument("--runs", help="default runs/seed004_EXPERIMENT")
        if command == "run":
            c.add_argument("--binary", default=str(ROOT / "build" / "grainflow"))
        else:
            c.add_argument("--out", help="default studies/seed004/results/vc_EXPERIMENT.json")
        c.set_defaults(func=func)
    args = p.parse_args()
    args.runs = args.runs or str(ROOT / "runs" / f"seed004_{args.experiment}")
    if args.command == "report":
        args.out = args.out or str(ROOT / "studies" / "seed004" / "results" / f"vc_{args.experiment}.json")
    args.func(args)


if __name__ == "__main__":
    main()
