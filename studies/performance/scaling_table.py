#!/usr/bin/env python3
"""The README's scaling table from a log of studies/performance/bench_scaling.sh (medians of 3 repetitions).

    studies/performance/bench_scaling.sh > studies/performance/results/scaling.log
    /usr/bin/python3 studies/performance/scaling_table.py studies/performance/results/scaling.log
"""
import re
import sys

LINE = re.compile(r"threads:(\d+)/real_time_median.*grains=([0-9.]+)([kM]?) particle_steps/s=([0-9.]+)([kMG]?)/s "
                  r"rebuilds/step=([0-9.]+)([munkMG]?)")
# Google Benchmark prints counters with SI prefixes (5m = 0.005).
SCALE = {"": 1.0, "k": 1e3, "M": 1e6, "G": 1e9, "m": 1e-3, "u": 1e-6, "n": 1e-9}


def one_thread_windows(paths):
    """Each window of studies/performance/bench_scaling.sh in the logs (one `# bench_scaling` header each) as
    {grains: one-thread particle-steps/s}."""
    windows = []
    for path in paths:
        for line in open(path):
            if line.startswith("# bench_scaling") or not windows:
                windows.append({})
            m = LINE.search(line)
            if m and int(m.group(1)) == 1:
                windows[-1][round(float(m.group(2)) * SCALE[m.group(3)])] = float(m.group(4)) * SCALE[m.group(5)]
    return [w for w in windows if w]


def main(path):
    rows = {}
    for line in open(path):
        m = LINE.search(line)
        if m:
            grains = round(float(m.group(2)) * SCALE[m.group(3)])
            rows.setdefault(grains, {})[int(m.group(1))] = (float(m.group(4)) * SCALE[m.group(5)],
                                                            float(m.group(6)) * SCALE[m.group(7)])
    print("| `bench/settled_layer`, 200 steps after settling | 1 thread | 2 threads | list rebuilds per step (1 / 2 threads) |")
    print("|---|---|---|---|")
    for grains in sorted(rows):
        r = rows[grains]
        print(f"| {grains:,} grains | {r[1][0]:.3g} | {r[2][0]:.3g} | {r[1][1]:.3g} / {r[2][1]:.3g} |")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "studies/performance/results/scaling.log")
