#!/usr/bin/env python3
"""The cost per grain against the grain count over several measurement windows: the one-thread
rates of every log of studies/performance/bench_scaling.sh given (each window is one invocation, its own
`# bench_scaling` header; each rate a median of 3 repetitions), per grain count the median and the
range over the windows, and each count's median against the largest count's.

    /usr/bin/python3 studies/performance/scaling_windows_table.py studies/performance/results/scaling_xeon.log studies/performance/results/scaling_knee_xeon.log studies/performance/results/scaling_small_xeon.log
"""
import statistics
import sys

sys.path.insert(0, __file__.rsplit("/", 1)[0])
from scaling_table import one_thread_windows  # noqa: E402


def main(paths):
    rates = {}
    for window in one_thread_windows(paths):
        for grains, rate in window.items():
            rates.setdefault(grains, []).append(rate)
    largest = statistics.median(rates[max(rates)])
    print("| grains | windows | particle-steps/s, 1 thread: median (range) | median against the largest layer's |")
    print("|---|---|---|---|")
    for grains in sorted(rates):
        r = rates[grains]
        med = statistics.median(r)
        print(f"| {grains:,} | {len(r)} | {med:.3g} ({min(r):.3g}–{max(r):.3g}) | {med / largest:.2f} |")


if __name__ == "__main__":
    main(sys.argv[1:])
