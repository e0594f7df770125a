#!/usr/bin/env python3
"""Design 1 of the seed-004 mixer with the representative-volume law, run from empty for 300 s with one
thing changed at a time, and Vc(L) of each: the median of layers.csv's pooled rows (20 s each) after
the hold-up is steady (from 150 s, as studies/seed004/mixer_report.py finds it), with the spread a
random mixture of the cells' visits gives (vc_sampling.py) beside it. Five experiments:

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
                 slip_0.1      friction regularised below 0.1 m/s: the control for 'swapped', which needs it
                 swapped       the other reading of the paper's coefficients, k_r and k_p swapped for grains
                               (k_r 0.15, k_p 15) and walls (k_r 0.1, k_p 10); friction regularised below 0.1 m/s
                               so that run.dt 6.5e-5 s stays under 0.1 of its time-step term (at 0.01 m/s it
                               would need 6.8e-6 s, 60 times the steps of the scene); run.max_overlap 1.0,
                               since a fed grain landing on the housing overlaps it by 0.40 of its diameter
                               at 0.35 s under the weaker approach force (1.1 against 11 of its separation
                               force) and the scene's 0.4 stops the run

  geometry     is the high Vc at 0.4 m the bladeless outlet compartment (0.40 to 0.5 m) that the scene adds?
               The seed reports Vc to L = 0.4 m and does not give the housing's length:
                 seed          the scene's: partitions at 0.16, 0.28 and 0.40 m, the end ring at 0.5 m
                 end_at_0.4    the end ring (its 0.08 m hole) where the last partition was, at 0.40 m: no
                               outlet compartment (scene written by scenes/generators/mixer_scene.py)
                 end_at_0.4_hole_0.06  the same with a 0.06 m outlet hole, to hold more
               Layers at and past the end ring (L + 11 mm > 0.40 m) lie outside this housing.

  partitions   does the key gather against the partitions because they hold back the bed's bottom, where the
               smaller key sinks? The seed has annular partitions but gives neither their height nor where
               they sit; the scene's rise 15 mm from the housing (inner radius 0.085 m):
                 seed          the scene's partitions at 0.16, 0.28 and 0.40 m, 15 mm high
                 rings_10mm    the same partitions 10 mm high (inner radius 0.09 m)
                 rings_30mm    30 mm high (inner radius 0.07 m)
                 none          no partitions: blades, the inlet wall and the end ring only

  feed         does the way the feed enters set Vc near the inlet? The seed feeds through a nozzle in the
               left end wall and gives neither its size nor where it points; the scene places batches in a
               box above the bed:
                 seed          the scene's: 25 g every 0.5 s at random in x 0.012 .. 0.045 m, y -0.01 .. 0.06 m,
                               z -0.045 .. 0.045 m, at rest
                 stream        the same box, 2.5 g every 0.05 s: about one model particle an event, a steady
                               trickle in place of batches
                 nozzle        2.5 g every 0.05 s into a 40 mm cube on the axis at the inlet wall (x 0.012 ..
                               0.052 m), at rest: a nozzle's mouth on the axis
                 nozzle_jet    the same mouth, the grains leaving it at 0.5 m/s along the axis

  vc_variants.py run EXPERIMENT [--only VARIANT ...] [--threads 1] [--binary build/grainflow] [--runs runs/seed004_EXPERIMENT]
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
NOZZLE = ["--set", 'feed.0.region={ shape = "box", lo = [0.012, -0.02, -0.02], hi = [0.052, 0.02, 0.02] }']
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
        "slip_0.1": ["--set", "contact.slip_speed=0.1"],
        "swapped": ["--set", "contact.kr=0.15", "--set", "contact.kp=15", "--set", "contact.wall.kr=0.1",
                    "--set", "contact.wall.kp=10", "--set", "contact.slip_speed=0.1", "--set", "run.dt=6.5e-5",
                    "--set", "run.max_overlap=1.0"],
    },
    "geometry": {
        "seed": [],
        "end_at_0.4": [],
        "end_at_0.4_hole_0.06": [],
    },
    "partitions": {
        "seed": [],
        "rings_10mm": [],
        "rings_30mm": [],
        "none": [],
    },
    "feed": {
        "seed": [],
        "stream": ["--set", "feed.0.interval=0.05"],
        "nozzle": ["--set", "feed.0.interval=0.05"] + NOZZLE,
        "nozzle_jet": ["--set", "feed.0.interval=0.05", "--set", "feed.0.velocity=[0.5, 0.0, 0.0]"] + NOZZLE,
    },
}
# Variants whose scene is another geometry, written by the generator into the run's folder.
SCENES = {("geometry", "end_at_0.4"): {"length": 0.40, "partitions": [0.16, 0.28]},
          ("geometry", "end_at_0.4_hole_0.06"): {"length": 0.40, "partitions": [0.16, 0.28], "outlet_hole": 0.06},
          ("partitions", "rings_10mm"): {"partition_hole": 0.09},
          ("partitions", "rings_30mm"): {"partition_hole": 0.07},
          ("partitions", "none"): {"partitions": []}}
STEADY_FROM = 150.0  # s


def median(v):
    s = sorted(v)
    n = len(s)
    return s[n // 2] if n % 2 else 0.5 * (s[n // 2 - 1] + s[n // 2])


def run(args):
    variants = EXPERIMENTS[args.experiment]
    unknown = sorted(set(args.only or []) - set(variants))
    if unknown:
        sys.exit(f"vc_variants.py: no variant {', '.join(unknown)} in {args.experiment}; "
                 f"it has {', '.join(variants)}")
    for name, extra in variants.items():
        if args.only and name not in args.only:
            continue
        out = pathlib.Path(args.runs) / name
        scene = SCENE
        if (args.experiment, name) in SCENES:
            sys.path.insert(0, str(ROOT / "scenes" / "generators"))
            import mixer_scene
            scene = pathlib.Path(args.runs) / f"{name}.toml"
            scene.parent.mkdir(parents=True, exist_ok=True)
            scene.write_text(mixer_scene.scene(1, **SCENES[(args.experiment, name)]))
        subprocess.run([args.binary, "run", str(scene), "--out", str(out), "--threads", str(args.threads)]
                       + QUIET + extra, check=True)


def layer_vc(folder):
    """Vc per layer over the pooled rows of layers.csv from STEADY_FROM: median, range, and the median
    Vc a random mixture of the cells' visits would give."""
    from grainflow.outputs import read_csv, rows_of
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
    return layers


def holdup(folder):
    """Median model particles and kg in the mixer from STEADY_FROM, and the largest overlap (of the smaller
    diameter) of the whole run (series.csv)."""
    from grainflow.outputs import read_csv, rows_of
    every = list(rows_of(read_csv(folder / "series.csv")))
    rows = [r for r in every if r["time"] >= STEADY_FROM]
    return {"grains": median([r["grains"] for r in rows]), "kg": median([r["holdup_mass"] for r in rows]),
            "max_overlap_ratio": max(r["max_overlap_ratio"] for r in every)}


def report(args):
    """Measures each variant whose run folder is here; keeps the committed results of those whose folder
    this checkout lacks, each with the build that ran it."""
    variants = EXPERIMENTS[args.experiment]
    out = pathlib.Path(args.out)
    kept = json.loads(out.read_text()) if out.exists() else {"vc": {}}
    result = {"scene": str(SCENE.relative_to(ROOT)), "steady_from_s": STEADY_FROM,
              "command": f"studies/seed004/vc_variants.py run {args.experiment} && "
                         f"studies/seed004/vc_variants.py report {args.experiment}",
              "variants": {n: variants[n] for n in variants},
              "scenes": {n: SCENES[(args.experiment, n)] for n in variants if (args.experiment, n) in SCENES},
              "vc": {}, "commits": {}, "holdup": {},
              "wall_seconds": {}}
    for name in variants:
        folder = pathlib.Path(args.runs) / name
        if not (folder / "summary.json").exists():
            if name not in kept["vc"]:
                sys.exit(f"vc_variants.py: no run of {name} in {folder} and none in {out}; "
                         f"run: vc_variants.py run {args.experiment} --only {name}")
            result["vc"][name] = kept["vc"][name]
            for key in ("commits", "holdup", "wall_seconds"):
                if name in kept.get(key, {}):
                    result[key][name] = kept[key][name]
            if name not in result["commits"] and "commit" in kept:
                result["commits"][name] = kept["commit"]
            continue
        summary = json.loads((folder / "summary.json").read_text())
        result["commits"][name] = summary.get("commit")
        result["wall_seconds"][name] = summary.get("wall_seconds")
        result["vc"][name] = layer_vc(folder)
        result["holdup"][name] = holdup(folder)
    pathlib.Path(args.out).write_text(json.dumps(result, indent=1) + "\n")
    names = list(variants)
    print("L (m)  " + "  ".join(f"{n:>22}" for n in names) + "   (Vc median %, random-mixture %)")
    for d in sorted({v["distance"] for n in names for v in result["vc"][n]}):
        cells = []
        for n in names:
            v = next((x for x in result["vc"][n] if x["distance"] == d), None)
            rnd = None if v is None else v["random_vc_median"]
            cells.append("-" if v is None else
                         f"{100 * v['vc_median']:5.1f} ({100 * v['vc_min']:4.1f}-{100 * v['vc_max']:4.1f}) "
                         + ("  -" if rnd is None else f"{100 * rnd:4.1f}"))
        print(f"{d:.3f}  " + "  ".join(f"{c:>22}" for c in cells))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    for command, func in (("run", run), ("report", report)):
        c = sub.add_parser(command)
        c.add_argument("experiment", choices=sorted(EXPERIMENTS))
        c.add_argument("--runs", help="default runs/seed004_EXPERIMENT")
        if command == "run":
            c.add_argument("--binary", default=str(ROOT / "build" / "grainflow"))
            c.add_argument("--only", nargs="+", metavar="VARIANT", help="run these variants only")
            c.add_argument("--threads", type=int, default=1)
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
