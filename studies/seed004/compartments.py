#!/usr/bin/env python3
"""Where the key component sits in each compartment of the seed-004 mixer, in steady state.

  compartments.py report [--runs runs/seed004] [--docs studies/seed004/results]
      For every finished run in studies/seed004/results/mixer.json (designs and sphere-DEM models), reads the
      VTK frames written from its steady state on (mixer.json's steady_from_s) and measures, per
      compartment between the inlet wall, the partitions and the end ring (mixer_scene.py):
        key_fraction     the key component's share of the compartment's solid volume (the feed's is
                         KEY_VOLUME_FRACTION)
        wall_minus_top   key fraction of the grains nearer the housing than the compartment's median
                         distance from it (the bed's wall side) minus that of the others (its free-
                         surface side), both by solid volume: > 0 when the key grains sink towards
                         the housing (percolation of the smaller key grains through the flowing layer,
                         as in a rotating drum's radial segregation), 0 when well mixed
        grains           grains in the compartment per frame
      each as the mean over the frames with the standard error of that mean (frames 10 s apart,
      several residence-time fractions apart, taken as independent). Writes compartments.json.
  compartments.py table studies/seed004/results/compartments.json
      The README's table (tools/readme/tables.py calls it; needs no numpy).
"""
import argparse
import json
import math
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scenes" / "generators"))
import mixer_scene as geometry  # noqa: E402  (the scenes' dimensions, one source)
from grainflow.vtp import read_vtp  # noqa: E402

BOUNDS = [0.0] + list(geometry.PARTITIONS) + [geometry.LENGTH]
NAMES = ["stage I", "stage II", "stage III", "outlet (no blades)"]
KEY_SPECIES = 1  # frames number species from 0; the scenes list the carrier first, the key second


def frame_times(run):
    """(time, file) of the run's frames from its frames.pvd."""
    text = (run / "frames.pvd").read_text()
    return [(float(t), run / f) for t, f in re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', text)]


def measure(frame):
    """Per compartment: (key fraction, wall-minus-top key fraction, grains) of one frame."""
    rows = []
    for (x, y, z), r, t in zip(frame["Points"], frame["radius"], frame["species"]):
        for c in range(len(NAMES)):
            if BOUNDS[c] <= x < BOUNDS[c + 1]:
                rows.append((c, geometry.RADIUS - math.hypot(y, z), r ** 3, t == KEY_SPECIES))
    result = []
    for c in range(len(NAMES)):
        mine = sorted((d, v, k) for cc, d, v, k in rows if cc == c)
        if len(mine) < 4:
            result.append(None)
            continue
        total = sum(v for _, v, _ in mine)
        key = sum(v for _, v, k in mine if k)
        half = len(mine) // 2
        def frac(part):
            vol = sum(v for _, v, _ in part)
            return sum(v for _, v, k in part if k) / vol if vol > 0 else float("nan")
        result.append((key / total, frac(mine[:half]) - frac(mine[half:]), len(mine)))
    return result


def mean_se(values):
    values = [v for v in values if v == v]
    n = len(values)
    if n == 0:
        return None, None
    m = sum(values) / n
    se = math.sqrt(sum((v - m) ** 2 for v in values) / (n - 1) / n) if n > 1 else None
    return m, se


def report(args):
    mixer = json.loads((pathlib.Path(args.docs) / "mixer.json").read_text())
    # The designs' runs, then the sphere-DEM runs (the models list repeats design 1 as its coarsest).
    runs = [(f"design{d['design']}", d) for d in mixer["designs"]]
    runs += [(f"dem_f{m['factor']:g}", m) for m in mixer["models"] if m.get("factor")]
    out = {"feed_key_volume_fraction": geometry.KEY_VOLUME_FRACTION, "compartments": NAMES,
           "bounds_m": BOUNDS, "runs": []}
    for name, entry in runs:
        kind = "sphere DEM" if name.startswith("dem") else "representative volumes"
        run = pathlib.Path(args.runs) / name
        if not (run / "frames.pvd").exists():
            continue
        frames = [(t, f) for t, f in frame_times(run) if t >= entry["steady_from_s"] - 1e-9]
        per = [measure(read_vtp(f)) for _, f in frames]
        row = {"run": name, "kind": kind, "frames": len(frames),
               "from_s": frames[0][0] if frames else None, "to_s": frames[-1][0] if frames else None, "compartments": []}
        for c in range(len(NAMES)):
            vals = [p[c] for p in per if p[c] is not None]
            kf, kf_se = mean_se([v[0] for v in vals])
            wt, wt_se = mean_se([v[1] for v in vals])
            ng, _ = mean_se([v[2] for v in vals])
            row["compartments"].append({"name": NAMES[c], "key_fraction": kf, "key_fraction_se": kf_se,
                                        "wall_minus_top": wt, "wall_minus_top_se": wt_se, "grains": ng})
        out["runs"].append(row)
        print(f"{name}: {len(frames)} frames from {row['from_s']} s")
    path = pathlib.Path(args.docs) / "compartments.json"
    path.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {path}")


def fmt(m, se):
    if m is None:
        return "—"
    return f"{m:+.2f} ± {se:.2f}" if se is not None else f"{m:+.2f}"


def table(args):
    d = json.loads(pathlib.Path(args.json).read_text())
    names = d["compartments"]
    print("| run | frames | " + " | ".join(names) + " |")
    print("|---|---|" + "---|" * len(names))
    for r in d["runs"]:
        cells = [f"{c['key_fraction']:.2f} / {fmt(c['wall_minus_top'], c['wall_minus_top_se'])} / "
                 f"{c['grains']:.0f}" if c["key_fraction"] is not None else "—" for c in r["compartments"]]
        print(f"| {r['run']} | {r['frames']} ({r['from_s']:.0f}–{r['to_s']:.0f} s) | " + " | ".join(cells) + " |")
    print()
    print(f"Each cell: key volume fraction (the feed's {d['feed_key_volume_fraction']:.2f}) / key fraction of the "
          "wall-side half of the compartment's grains minus the free-surface half's, mean ± standard error over "
          "the frames / grains per frame.")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("report")
    r.add_argument("--runs", default=str(ROOT / "runs" / "seed004"))
    r.add_argument("--docs", default=str(ROOT / "studies" / "seed004" / "results"))
    t = sub.add_parser("table")
    t.add_argument("json")
    args = p.parse_args()
    report(args) if args.cmd == "report" else table(args)


if __name__ == "__main__":
    main()
