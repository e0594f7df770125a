#!/usr/bin/python3
"""Alternated rounds of the liquid step benchmark (bench/mps_step_bench.cpp) for two builds, A then B in
every round, so that a drift of the shared machine's speed falls on both; one CSV row per build and round.

    /usr/bin/python3 studies/seed003/step_rounds.py run --a NAME=BINARY --b NAME=BINARY \\
        [--filter 'dim:3/side:46/eigen:0'] [--filter-b FILTER] [--rounds 5] [--out studies/seed003/results/step_rounds.csv]
    /usr/bin/python3 studies/seed003/step_rounds.py table studies/seed003/results/step_rounds.csv [--per solve]

--filter-b gives B another benchmark than A (one build's two solvers: eigen:1 against eigen:0). The table gives
each build's median ms per step with its range, and the per-round ratio A/B (median, range).
"""
import argparse
import csv
import json
import statistics
import subprocess
import tempfile
from pathlib import Path


def one(binary, flt):
    with tempfile.NamedTemporaryFile(suffix=".json") as out:
        subprocess.run([binary, f"--benchmark_filter={flt}", "--benchmark_min_time=1",
                        f"--benchmark_out={out.name}", "--benchmark_out_format=json"],
                       check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        data = json.loads(Path(out.name).read_text())
    b = [x for x in data["benchmarks"] if x.get("run_type", "iteration") == "iteration"][0]
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
    return b["name"], b["real_time"] * scale, b.get("ppe_iterations", 0.0), data["context"]["date"]


def run(a):
    builds = [tuple(a.a.split("=", 1)), tuple(a.b.split("=", 1))]
    a.out.parent.mkdir(parents=True, exist_ok=True)
    with open(a.out, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["round", "build", "benchmark", "ms_per_step", "ppe_iterations", "date"])
        for r in range(a.rounds):
            for (name, binary), flt in zip(builds, (a.filter, a.filter_b or a.filter)):
                bench, ms, iters, date = one(binary, flt)
                w.writerow([r, name, bench, f"{ms:.4f}", f"{iters:.1f}", date])
                fh.flush()
                print(f"round {r} {name}: {ms:.1f} ms per step")


def table(path, per="step"):
    rows = list(csv.DictReader(open(path)))
    names = list(dict.fromkeys(r["build"] for r in rows))
    by = {(int(r["round"]), r["build"]): float(r["ms_per_step"]) for r in rows}
    rounds = sorted({k[0] for k in by})
    print(f"| build | rounds | median ms per {per} | range | {names[0]} / {names[1]} per round: median (range) |")
    print("|---|---|---|---|---|")
    ratios = [by[(r, names[0])] / by[(r, names[1])] for r in rounds]
    for i, n in enumerate(names):
        v = [by[(r, n)] for r in rounds]
        ratio = f"{statistics.median(ratios):.2f} ({min(ratios):.2f}–{max(ratios):.2f})" if i == 1 else ""
        print(f"| {n} | {len(v)} | {statistics.median(v):.0f} | {min(v):.0f}–{max(v):.0f} | {ratio} |")
    benches = ", ".join(f"`{b}`" for b in dict.fromkeys(r["benchmark"] for r in rows))
    print(f"\nBenchmark {benches}, rounds run {rows[0]['date'][:10]}.")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("--a", required=True)
    r.add_argument("--b", required=True)
    r.add_argument("--filter", default="dim:3/side:46/eigen:0")
    r.add_argument("--filter-b", default=None)
    r.add_argument("--rounds", type=int, default=5)
    r.add_argument("--out", type=Path, default=Path("studies/seed003/results/step_rounds.csv"))
    t = sub.add_parser("table")
    t.add_argument("csv", type=Path)
    t.add_argument("--per", default="step", help="what one benchmark iteration is (step, solve)")
    a = ap.parse_args()
    run(a) if a.cmd == "run" else table(a.csv, a.per)


if __name__ == "__main__":
    main()
