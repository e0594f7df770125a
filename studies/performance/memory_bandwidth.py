#!/usr/bin/python3
"""One core's memory bandwidth on this machine, for reading the scaling table: a copy of a 256 MB
array of doubles with numpy, best of ten, in bytes read plus bytes written per second, and of a
2 GB one, best of three (past the last-level cache of either machine kind here: 32 MB on the EPYC,
hundreds of MB on the Xeon, where 256 MB may still sit in it). Also the same copy of arrays that fit
the last-level cache (8 MB) and the core's L2 (256 kB), for the cost ratio of a working set in and
out of cache. The processor's name is recorded with them.

    /usr/bin/python3 studies/performance/memory_bandwidth.py > studies/performance/results/memory_bandwidth.json
"""
import json
import os
import time

import numpy as np


def copy_rate(n_bytes, repeats):
    n = n_bytes // 8
    a = np.ones(n)
    b = np.empty_like(a)
    b[...] = a  # touch the pages
    best = float("inf")
    for _ in range(repeats):
        t0 = time.perf_counter()
        b[...] = a
        best = min(best, time.perf_counter() - t0)
    return 2 * n * 8 / best  # bytes read + bytes written, per second


def cpu_name():
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    return "unknown"


def main():
    out = {"date": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()), "cpus": os.cpu_count(),
           "load": os.getloadavg(), "cpu": cpu_name(), "method": "numpy copy b[...] = a, best of the repeats, (read + written) bytes / s"}
    for name, size, reps in (("dram_2GB", 2048 << 20, 3), ("dram_256MB", 256 << 20, 10), ("llc_8MB", 8 << 20, 200), ("l2_256kB", 256 << 10, 5000)):
        out[name + "_GBps"] = copy_rate(size, reps) / 1e9
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
