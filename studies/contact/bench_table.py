#!/usr/bin/python3
"""Medians and ranges of the alternated throughput runs that studies/contact/bench_before_after.sh writes.

    /usr/bin/python3 studies/contact/bench_table.py studies/contact/results/bench_before_after.csv A_LABEL B_LABEL
Prints one row per build and thread count, and the per-round ratio B/A (median and range).
    /usr/bin/python3 studies/contact/bench_table.py FILE LABEL --pooled
One row per thread count over every run of the file (both columns the same build).
    /usr/bin/python3 studies/contact/bench_table.py studies/contact/results/bench_kernels.csv A_LABEL B_LABEL --kernels
One row per kernel of studies/contact/bench_kernels.sh: medians and minima of both builds, ratio B/A per round.
"""
import csv
import statistics
import sys
from collections import defaultdict


def main(path, label_a, label_b):
    runs = defaultdict(dict)  # (threads, round) -> build -> rate
    for row in csv.DictReader(open(path, newline="")):
        runs[(int(row["threads"]), int(row["round"]))][row["build"]] = float(row["particle_steps_per_s"])
    print(f"| build | threads | rounds | median particle-steps/s | range | {label_b} / {label_a} per round: median (range) |")
    print("|---|---|---|---|---|---|")
    for t in sorted({k[0] for k in runs}):
        rounds = [v for k, v in sorted(runs.items()) if k[0] == t and "A" in v and "B" in v]
        ratios = [r["B"] / r["A"] for r in rounds]
        for build, label in (("A", label_a), ("B", label_b)):
            x = [r[build] for r in rounds]
            ratio = f"{statistics.median(ratios):.3f} ({min(ratios):.3f}–{max(ratios):.3f})" if build == "B" else ""
            print(f"| {label} | {t} | {len(x)} | {statistics.median(x):.3g} | {min(x):.3g}–{max(x):.3g} | {ratio} |")


def pooled(path, label):
    rates = defaultdict(list)
    for row in csv.DictReader(open(path, newline="")):
        rates[int(row["threads"])].append(float(row["particle_steps_per_s"]))
    print("| build | threads | runs | median particle-steps/s | range |")
    print("|---|---|---|---|---|")
    for t, x in sorted(rates.items()):
        print(f"| {label} | {t} | {len(x)} | {statistics.median(x):.3g} | {min(x):.3g}–{max(x):.3g} |")


def kernels(path, label_a, label_b):
    runs = defaultdict(dict)  # (kernel, round) -> build -> seconds
    for row in csv.DictReader(open(path, newline="")):
        runs[(row["kernel"], int(row["round"]))][row["build"]] = float(row["seconds"])
    print(f"| kernel (1 thread) | rounds | {label_a}: median (min) | {label_b}: median (min) "
          f"| {label_b} / {label_a} time per round: median (range) |")
    print("|---|---|---|---|---|")
    for k in dict.fromkeys(key[0] for key in runs):
        rounds = [v for key, v in sorted(runs.items()) if key[0] == k and "A" in v and "B" in v]
        a, b = [r["A"] for r in rounds], [r["B"] for r in rounds]
        ratios = [r["B"] / r["A"] for r in rounds]
        fmt = lambda x: f"{statistics.median(x) * 1e6:.1f} µs ({min(x) * 1e6:.1f})"
        print(f"| `{k}` | {len(rounds)} | {fmt(a)} | {fmt(b)} | "
              f"{statistics.median(ratios):.3f} ({min(ratios):.3f}–{max(ratios):.3f}) |")


if __name__ == "__main__":
    if len(sys.argv) > 4 and sys.argv[4] == "--kernels":
        kernels(*sys.argv[1:4])
    elif len(sys.argv) > 3 and sys.argv[3] == "--pooled":
        pooled(sys.argv[1], sys.argv[2])
    else:
        main(*sys.argv[1:4])
