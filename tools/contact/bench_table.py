#!/usr/bin/python3
"""Medians and ranges of the alternated throughput runs that tools/contact/bench_before_after.sh writes.

    /usr/bin/python3 tools/contact/bench_table.py docs/contact/bench_before_after.csv A_LABEL B_LABEL
Prints one row per build and thread count, and the per-round ratio B/A (median and range).
    /usr/bin/python3 tools/contact/bench_table.py FILE LABEL --pooled
One row per thread count over every run of the file (both columns the same build).
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


if __name__ == "__main__":
    if len(sys.argv) > 3 and sys.argv[3] == "--pooled":
        pooled(sys.argv[1], sys.argv[2])
    else:
        main(*sys.argv[1:4])
