#!/usr/bin/env python3
"""Seed 004's mixer (design 1, representative volumes, fed and emptied) on one rank and on two.

  mixer_ranks.py run [--out runs/mpi_mixer]
      grainflow on one process and grainflow_mpi on two ranks (one thread each), the whole 300 s.
  mixer_ranks.py compare [--out runs/mpi_mixer] [--docs studies/mpi/results]
      The steady state, hold-up, mean residence time and Vc(L) of both runs, measured as
      studies/seed004/mixer_report.py measures the design runs, into studies/mpi/results/mixer_ranks.json; the
      runs' series, layers, residence and summary files are copied under studies/mpi/results/mixer_ranks/.
  mixer_ranks.py table [studies/mpi/results/mixer_ranks.json]
      The README's table (tools/readme/tables.py calls it).

The runs start alike and part in the last bits within seconds (the force sums run in another order
on two ranks), so they are compared as two samples of one steady state: against the spread of the
pooled rows within each run.
"""
import argparse
import json
import pathlib
import shutil
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "studies" / "seed004"))
import mixer_report as report  # noqa: E402  (the design runs' measures, one source)

SCENE = "scenes/mixer_seed004_design1.toml"
KEPT = ["series.csv", "layers.csv", "residence.csv", "summary.json"]


def run(args):
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    subprocess.run([str(ROOT / "build/grainflow"), "run", SCENE, "--out", str(out / "one"), "--threads", "1",
                    "--quiet"], cwd=ROOT, check=True)
    subprocess.run(["mpiexec", "--allow-run-as-root", "--oversubscribe", "-n", "2", str(ROOT / "build/grainflow_mpi"),
                    "run", SCENE, "--out", str(out / "two"), "--threads", "1"], cwd=ROOT, check=True)


def measures(folder):
    series = report.read_csv(folder / "series.csv")
    layers = report.read_csv(folder / "layers.csv")
    residence = report.read_csv(folder / "residence.csv")
    summary = report.summary_of(folder)
    t0, level = report.steady_start(series)
    stats, _ = report.rtd(residence, t0)
    return {"steady_from_s": t0, "holdup_mass_kg": level, "fed_kg": float(series["fed_mass"][-1]),
            "discharged_kg": float(series["discharged_mass"][-1]), "discharged_grains": int(len(residence["id"])),
            "rtd_mean_s": stats.get("mean"), "rtd_grains": stats.get("grains"),
            "wall_seconds": summary["wall_seconds"], "particle_steps_per_second": summary["particle_steps_per_second"],
            "ranks": summary.get("ranks", 1), "vc": report.vc_profile(layers, t0)}


def compare(args):
    out, docs = pathlib.Path(args.out), pathlib.Path(args.docs)
    result = {"scene": SCENE, "threads_per_process": 1}
    for name in ("one", "two"):
        result[name] = measures(out / name)
        keep = docs / "mixer_ranks" / name
        keep.mkdir(parents=True, exist_ok=True)
        for f in KEPT:
            shutil.copyfile(out / name / f, keep / f)
    (docs / "mixer_ranks.json").write_text(json.dumps(result, indent=1) + "\n")


def table(args):
    r = json.loads(pathlib.Path(args.file).read_text())
    one, two = r["one"], r["two"]
    rows = ["| measure | one process | two ranks |", "|---|---|---|"]
    rows.append(f"| steady from (s) | {one['steady_from_s']:.0f} | {two['steady_from_s']:.0f} |")
    rows.append(f"| hold-up in steady state (kg) | {one['holdup_mass_kg']:.3f} | {two['holdup_mass_kg']:.3f} |")
    rows.append(f"| fed / discharged by 300 s (kg) | {one['fed_kg']:.3f} / {one['discharged_kg']:.3f} | "
                f"{two['fed_kg']:.3f} / {two['discharged_kg']:.3f} |")
    rows.append(f"| mean residence time of the grains fed and discharged in steady state (s, grains) | "
                f"{one['rtd_mean_s']:.1f} ({one['rtd_grains']}) | {two['rtd_mean_s']:.1f} ({two['rtd_grains']}) |")
    for a, b in zip(one["vc"], two["vc"]):
        if a["pools"] == 0 or b["pools"] == 0:
            continue
        rows.append(f"| Vc at L = {a['distance']:.3f} m: mean of the steady pools (their range) | "
                    f"{100 * a['vc_mean']:.1f} % ({100 * a['vc_min']:.1f}–{100 * a['vc_max']:.1f}) | "
                    f"{100 * b['vc_mean']:.1f} % ({100 * b['vc_min']:.1f}–{100 * b['vc_max']:.1f}) |")
    rows.append(f"| wall time (s), particle-steps/s, one thread a process | {one['wall_seconds']:.0f}, "
                f"{one['particle_steps_per_second']:.3g} | {two['wall_seconds']:.0f}, {two['particle_steps_per_second']:.3g} |")
    print("\n".join(rows))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    a = sub.add_parser("run")
    a.add_argument("--out", default="runs/mpi_mixer")
    a.set_defaults(fn=run)
    a = sub.add_parser("compare")
    a.add_argument("--out", default="runs/mpi_mixer")
    a.add_argument("--docs", default="studies/mpi/results")
    a.set_defaults(fn=compare)
    a = sub.add_parser("table")
    a.add_argument("file", nargs="?", default="studies/mpi/results/mixer_ranks.json")
    a.set_defaults(fn=table)
    args = p.parse_args()
    args.fn(args)


if __name__ == "__main__":
    main()
