#!/usr/bin/env python3
"""The default drum with analytic walls against the same drum built from triangle meshes.

  mesh_drum_compare.py run [--seeds 1 2 3] [--binary build/grainflow] [--threads 1]
      Runs scenes/drum_quick.toml and scenes/drum_quick_mesh.toml with run.seed = each seed (the
      fill's placement follows it; the same pour in both) into runs/mesh_drum/<wall>_s<seed>;
      finished runs are skipped.
  mesh_drum_compare.py report [--docs studies/walls/results]
      For each run, the time means over the flowing part (t >= 1 s of rotation) of the translational
      kinetic energy, the segregation (Danckwerts) index and Lacey's index, and their values at the
      end. The noise is the spread between the seeds of one wall kind; the mesh drum agrees when its
      seed mean differs from the analytic seed mean by less than the 95 % point of Student's t times
      the standard error of that difference (from the spread between seeds of each kind).
      Writes mesh_drum_compare.json, mesh_drum_series.csv and mesh_drum_compare.png.
"""
import argparse
import json
import math
import pathlib
import statistics
import subprocess
import sys

try:  # the README's table needs only the JSON; reports and charts need numpy
    import numpy as np
except ImportError:
    np = None

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))
SCENES = {"analytic": ROOT / "scenes" / "drum_quick.toml", "mesh": ROOT / "scenes" / "drum_quick_mesh.toml"}
RUNS = ROOT / "runs" / "mesh_drum"
FLOWING_FROM = 1.0  # s of rotation: the bed avalanches from about 0.5 s at 1.5 rad/s
MEASURES = ["ke_translational", "segregation_index", "lacey_index"]
T95 = {2: 4.303, 4: 2.776, 6: 2.447, 8: 2.306, 10: 2.228}  # two-sided 95 % points of Student's t


def completed(folder):
    """Whether the run folder holds a completed run (its summary.json says so)."""
    from grainflow.outputs import Run
    return folder.is_dir() and Run(folder).has("summary.json") and Run(folder).status == "completed"


def run(args):
    for seed in args.seeds:
        for kind, scene in SCENES.items():
            out = RUNS / f"{kind}_s{seed}"
            if completed(out):
                continue
            cmd = [args.binary, "run", str(scene), "--out", str(out), "--threads", str(args.threads), "--quiet",
                   "--set", f"run.seed={seed}", "--set", "output.frame_interval=0",
                   # The pour's region 0.1 mm inside the drum: the mantle's facets lie up to 5 um
                   # inside the radius, and a grain poured against the analytic surface would overlap them.
                   "--set", "fill.0.region.radius=0.0399"]
            print(" ".join(cmd), flush=True)
            subprocess.run(cmd, check=True)


def load(kind, seed):
    """series.csv of one run as {column: array}."""
    from grainflow.outputs import Run
    return Run(RUNS / f"{kind}_s{seed}").series


def report(args):
    docs = pathlib.Path(args.docs)
    docs.mkdir(parents=True, exist_ok=True)
    from grainflow.outputs import Run
    seeds = sorted({int(p.name.split("_s")[1]) for p in RUNS.glob("*_s*") if completed(p)})
    seeds = [s for s in seeds if all((RUNS / f"{k}_s{s}" / "summary.json").exists() for k in SCENES)]
    result = {"flowing_from_s": FLOWING_FROM, "seeds": seeds, "measures": {}}
    series = {}
    for kind in SCENES:
        for s in seeds:
            series[(kind, s)] = load(kind, s)
    for m in MEASURES:
        entry = {}
        for kind in SCENES:
            means = [float(np.nanmean(series[(kind, s)][m][series[(kind, s)]["time"] >= FLOWING_FROM])) for s in seeds]
            ends = [float(series[(kind, s)][m][-1]) for s in seeds]
            entry[kind] = {"time_mean_per_seed": means, "mean": float(np.mean(means)),
                           "range": [float(np.min(means)), float(np.max(means))], "end_per_seed": ends}
        a, b = entry["analytic"], entry["mesh"]
        # The noise of the difference of two seed means: the standard error from each kind's spread
        # between seeds; the difference counts as noise within the 95 % point of Student's t for
        # 2 (n - 1) degrees of freedom (2.776 for three seeds each).
        se = math.sqrt(np.var(a["time_mean_per_seed"], ddof=1) / len(seeds) +
                       np.var(b["time_mean_per_seed"], ddof=1) / len(seeds))
        entry["difference"] = b["mean"] - a["mean"]
        entry["standard_error"] = se
        entry["t"] = entry["difference"] / se if se > 0 else float("inf")
        entry["t_95"] = T95[2 * (len(seeds) - 1)]
        entry["within_noise"] = abs(entry["t"]) <= entry["t_95"]
        result["measures"][m] = entry
    for kind in SCENES:
        result[kind + "_wall_seconds"] = [Run(RUNS / f"{kind}_s{s}").summary["wall_seconds"] for s in seeds]
    (docs / "mesh_drum_compare.json").write_text(json.dumps(result, indent=1) + "\n")
    with open(docs / "mesh_drum_series.csv", "w") as f:
        f.write("wall,seed,time," + ",".join(MEASURES) + "\n")
        for (kind, s), d in sorted(series.items()):
            for k in range(len(d["time"])):
                f.write(f"{kind},{s},{d['time'][k]:.4g}," + ",".join(f"{d[m][k]:.6g}" for m in MEASURES) + "\n")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(MEASURES), figsize=(11, 3.2))
    for ax, m in zip(axes, MEASURES):
        for (kind, s), d in sorted(series.items()):
            ax.plot(d["time"], d[m], color="C0" if kind == "analytic" else "C3", lw=0.8,
                    label=kind if s == seeds[0] else None)
        ax.set_xlabel("time (s)")
        ax.set_title(m, fontsize=9)
        ax.axvline(FLOWING_FROM, color="grey", ls=":", lw=0.6)
    axes[0].set_yscale("log")
    axes[0].legend(fontsize=8)
    fig.suptitle("Default drum: analytic walls (blue) against triangle-mesh walls (red), one line per seed", fontsize=9)
    fig.tight_layout()
    fig.savefig(docs / "mesh_drum_compare.png", dpi=110)
    print(json.dumps(result["measures"], indent=1))


def table(args):
    r = json.loads(pathlib.Path(args.file).read_text())
    rows = [f"| measure (time mean from {r['flowing_from_s']:g} s) | analytic walls (mean, range over seeds) | "
            "mesh walls | difference | its standard error | t | within noise (95 %) |", "|---|---|---|---|---|---|---|"]
    for m, e in r["measures"].items():
        a, b = e["analytic"], e["mesh"]
        rows.append(f"| {m} | {a['mean']:.4g} ({a['range'][0]:.4g}–{a['range'][1]:.4g}) | {b['mean']:.4g} "
                    f"({b['range'][0]:.4g}–{b['range'][1]:.4g}) | {e['difference']:+.3g} | {e['standard_error']:.3g} | "
                    f"{e['t']:+.1f} | {'yes' if e['within_noise'] else 'no'} (limit {e['t_95']:.2f}) |")
    rows.append("")
    rows.append(f"Seeds {', '.join(map(str, r['seeds']))}; wall time per run (1 thread): analytic "
                f"{statistics.median(r['analytic_wall_seconds']):.0f} s, mesh {statistics.median(r['mesh_wall_seconds']):.0f} s (medians).")
    print("\n".join(rows))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    r.add_argument("--binary", default=str(ROOT / "build" / "grainflow"))
    r.add_argument("--threads", type=int, default=1)
    p = sub.add_parser("report")
    p.add_argument("--docs", default=str(ROOT / "studies" / "walls" / "results"))
    t = sub.add_parser("table")
    t.add_argument("file")
    args = ap.parse_args()
    {"run": run, "report": report, "table": table}[args.cmd](args)


if __name__ == "__main__":
    main()
