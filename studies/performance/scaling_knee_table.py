#!/usr/bin/env python3
"""The README's table of where the cost per grain bends: a log of studies/performance/bench_scaling.sh at one
thread over several sizes (with grainflow check's memory estimate per size) and the machine's copy
bandwidth (studies/performance/memory_bandwidth.py).

    SIZES="0.0418 0.0591 0.0935 0.1321 0.1869 0.2955 0.4178" THREADS=1 studies/performance/bench_scaling.sh > studies/performance/results/scaling_knee.log
    /usr/bin/python3 studies/performance/memory_bandwidth.py > studies/performance/results/memory_bandwidth.json
    /usr/bin/python3 studies/performance/scaling_knee_table.py studies/performance/results/scaling_knee.log studies/performance/results/memory_bandwidth.json
"""
import json
import re
import sys

sys.path.insert(0, __file__.rsplit("/", 1)[0])
from scaling_table import LINE, SCALE  # noqa: E402

MEMORY = re.compile(r"^L=([0-9.]+) m\s+memory estimate, simulation arrays: ([0-9.]+) MiB \((\d+) bytes per grain")


def main(log, bandwidth):
    rate, memory = {}, {}
    for line in open(log):
        m = MEMORY.match(line)
        if m:
            memory[m.group(1)] = (float(m.group(2)), int(m.group(3)))
            continue
        m = LINE.search(line)
        if m and int(m.group(1)) == 1:
            size = line.split()[0].split("=")[1]
            rate[size] = (round(float(m.group(2)) * SCALE[m.group(3)]), float(m.group(4)) * SCALE[m.group(5)])
    sizes = sorted(rate, key=lambda s: rate[s][0])
    first = rate[sizes[0]][1]
    print("| grains | simulation arrays (MiB) | particle-steps/s, 1 thread | per grain, against the smallest layer | ns per particle-step |")
    print("|---|---|---|---|---|")
    for s in sizes:
        grains, r = rate[s]
        mib = f"{memory[s][0]:g}" if s in memory else "—"
        print(f"| {grains:,} | {mib} | {r:.3g} | {r / first:.2f} | {1e9 / r:.0f} |")
    b = json.load(open(bandwidth))
    per_grain = {v[1] for v in memory.values()}
    print()
    big = f"{b['dram_2GB_GBps']:.0f} GB/s for 2 GB, " if "dram_2GB_GBps" in b else ""
    where = f", {b['cpu']}" if "cpu" in b else ""
    print(f"Arrays {'/'.join(map(str, sorted(per_grain)))} bytes per grain (`grainflow check`); one core's copy bandwidth "
          f"(read + written, numpy, {b['date']}{where}): {big}{b['dram_256MB_GBps']:.0f} GB/s for 256 MB, "
          f"{b['llc_8MB_GBps']:.0f} GB/s for 8 MB, {b['l2_256kB_GBps']:.0f} GB/s for 256 kB.")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
