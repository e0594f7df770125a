#!/usr/bin/env python3
"""The README's per-system benchmark table from studies/performance/results/*.json (studies/performance/system_benchmarks.sh).

Each cell is the median time of five repetitions and the rate it implies (the benchmark's items per
call divided by that median time), so the two figures in a cell always agree.
"""
import json
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[2]
ROWS = [  # (file, benchmark family, label, items counter, unit)
    ("pair_contact", "BM_PairForces/simd", "`pair_contact_bench` xsimd", "pairs", "M pairs/s"),
    ("pair_contact", "BM_PairForces/scalar", "`pair_contact_bench` scalar twin (same slab sums)", "pairs", "M pairs/s"),
    ("wall_contact", "BM_WallForces/simd", "`wall_contact_bench` xsimd (3 walls)", "rows", "M rows/s"),
    ("wall_contact", "BM_WallForces/scalar", "`wall_contact_bench` scalar twin", "rows", "M rows/s"),
    ("broadphase", "BM_NeighborRebuild", "`broadphase_bench` full neighbour rebuild", "pairs", "M pairs/s"),
    ("broadphase", "BM_NeedsRebuild", "`broadphase_bench` skin check", "rows", "M rows/s"),
    ("integrate", "BM_KickDrift", "`integrate_bench` kick + drift", "rows", "M rows/s"),
    ("integrate", "BM_Kick", "`integrate_bench` kick", "rows", "M rows/s"),
]


def medians(name):
    data = json.loads((ROOT / "studies/performance/results" / f"{name}.json").read_text())
    out = {}
    for b in data["benchmarks"]:
        if b.get("aggregate_name") == "median":
            out[b["run_name"]] = b
    return out, data["context"]


def cell(b, counter, unit):
    t = b["real_time"]
    scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b["time_unit"]]
    rate = b[counter] / (t * scale) / 1e6
    shown = f"{t:.3g} {b['time_unit'].replace('us', 'µs')}"
    return f"{rate:.4g} {unit} ({shown})"


def main():
    print("| benchmark | items per call | 1 thread | 2 threads |")
    print("|---|---|---|---|")
    loads, commits = set(), set()
    for name, family, label, counter, unit in ROWS:
        m, ctx = medians(name)
        loads.add(ctx.get("load", "?"))
        commits.add(ctx.get("commit", "?"))
        one, two = m[f"{family}/threads:1/real_time"], m[f"{family}/threads:2/real_time"]
        print(f"| {label} | {int(one[counter]):,} {counter} | {cell(one, counter, unit)} | {cell(two, counter, unit)} |")
    print(f"\nMedians of 5 repetitions; commit {', '.join(sorted(commits))}; load averages at the start of each "
          f"file: {'; '.join(sorted(loads))}.")


if __name__ == "__main__":
    main()
