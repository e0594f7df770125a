#!/usr/bin/env python3
"""Composite bodies on ranks: speed of the contacts shared out (grainflow_mpi) against one process.

  body_ranks.py settle [--checkpoint runs/mpi_bodies/settled]
      The starting state: the prism hopper's settling stage on 2 ranks (grainflow_mpi), stopped as
      the gate would open (--steps 0), its checkpoint at the end (about 5 min here).
  body_ranks.py run [--checkpoint C] [--steps N] [--rounds R] [--out studies/mpi/results/body_ranks.json]
      From one checkpoint of a body scene (default: the seed-002 prism hopper settled on its closed
      gate, runs/mpi_bodies/settled), N main-stage steps (the gate opens: the discharge's first
      steps) by grainflow on 1 thread, by grainflow on 2 threads and by grainflow_mpi on 2 ranks of 1
      thread, in R alternated rounds. Every run continues the same state bit for bit, so each does
      the same work; the final series rows are checked to be byte-identical. Body-steps/s from each
      run's summary.json (its main stage, outputs included), median and range per configuration.
  body_ranks.py table [studies/mpi/results/body_ranks.json]
      The README's table (tools/readme/tables.py calls it).

Stop other work on the machine first: a run in the background takes a core and its cache.
"""
import argparse
import json
import pathlib
import shutil
import statistics
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))


def _outputs():
    """grainflow.outputs, imported where run files are read: it needs numpy, the tables do not."""
    import grainflow.outputs
    return grainflow.outputs


SCENE = "scenes/hopper_seed002_prisms.toml"
CONFIGS = [
    ("grainflow, 1 thread", ["build/grainflow", "run"], ["--threads", "1"]),
    ("grainflow, 2 threads", ["build/grainflow", "run"], ["--threads", "2"]),
    ("grainflow_mpi, 2 ranks x 1 thread",
     ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-n", "2", "build/grainflow_mpi", "run"], ["--threads", "1"]),
]


def one_run(config, settled, steps, work):
    name, program, threads = config
    out = pathlib.Path(work) / name.replace(" ", "_").replace(",", "")
    if out.exists():
        shutil.rmtree(out)
    shutil.copytree(settled, out)
    cmd = program + [SCENE, "--out", str(out), "--steps", str(steps), "--quiet", "--resume",
                     str(out / "checkpoints" / "checkpoint.gfc"), "--set", "output.frame_interval=0",
                     "--set", "output.picture_interval=0"] + threads
    subprocess.run([c if not c.startswith("build/") else str(ROOT / c) for c in cmd], cwd=ROOT, check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    summary = _outputs().Run(out).summary
    last = (out / "series.csv").read_text().strip().splitlines()[-1]  # the text: bit for bit across configs
    return summary, last


def settle(args):
    subprocess.run(["mpiexec", "--allow-run-as-root", "--oversubscribe", "-n", "2", str(ROOT / "build/grainflow_mpi"),
                    "run", SCENE, "--out", args.checkpoint, "--steps", "0", "--threads", "1", "--quiet"],
                   cwd=ROOT, check=True)


def run(args):
    settled = pathlib.Path(args.checkpoint)
    base = _outputs().Run(settled).summary
    result = {"scene": SCENE, "checkpoint": str(settled), "steps": args.steps, "rounds": args.rounds,
              "bodies": base["bodies"], "configs": {}}
    finals = set()
    with tempfile.TemporaryDirectory() as work:
        for r in range(args.rounds):
            for config in CONFIGS:
                summary, last = one_run(config, settled, args.steps, work)
                finals.add(last)
                entry = result["configs"].setdefault(config[0], {"body_steps_per_second": [], "wall_seconds": []})
                entry["body_steps_per_second"].append(summary["body_steps_per_second"])
                entry["wall_seconds"].append(summary["wall_seconds"])
                print(f"round {r + 1}: {config[0]}: {summary['body_steps_per_second']:.4g} body-steps/s", flush=True)
    result["final_series_rows_identical"] = len(finals) == 1
    result["final_series_row"] = sorted(finals)[0]
    for entry in result["configs"].values():
        v = entry["body_steps_per_second"]
        entry["median"], entry["min"], entry["max"] = statistics.median(v), min(v), max(v)
    ref = result["configs"][CONFIGS[0][0]]["median"]
    for entry in result["configs"].values():
        entry["speedup_vs_one_thread"] = entry["median"] / ref
    pathlib.Path(args.out).write_text(json.dumps(result, indent=2) + "\n")
    print(f"wrote {args.out}; final rows identical: {result['final_series_rows_identical']}")


def table(args):
    d = json.loads(pathlib.Path(args.file).read_text())
    print("| run | body-steps/s, median | range | speed-up over 1 thread |")
    print("|---|---|---|---|")
    for name, e in d["configs"].items():
        print(f"| {name} | {e['median']:.3g} | {e['min']:.3g}–{e['max']:.3g} | {e['speedup_vs_one_thread']:.2f} |")
    print()
    print(f"{d['bodies']['moving']} moving prisms (+ {d['bodies']['fixed']} fixed), {d['steps']} steps from the settled "
          f"pour as the gate opens, {d['rounds']} alternated rounds; final series rows byte-identical across all runs: "
          f"{'yes' if d['final_series_rows_identical'] else 'NO'}.")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    st = sub.add_parser("settle")
    st.add_argument("--checkpoint", default="runs/mpi_bodies/settled")
    r = sub.add_parser("run")
    r.add_argument("--checkpoint", default="runs/mpi_bodies/settled")
    r.add_argument("--steps", type=int, default=3000)
    r.add_argument("--rounds", type=int, default=5)
    r.add_argument("--out", default="studies/mpi/results/body_ranks.json")
    t = sub.add_parser("table")
    t.add_argument("file", nargs="?", default=str(ROOT / "studies/mpi/results/body_ranks.json"))
    args = p.parse_args()
    {"settle": settle, "run": run, "table": table}[args.cmd](args)


if __name__ == "__main__":
    sys.exit(main())
