#!/usr/bin/python3
"""One core's memory bandwidth on this machine, for reading the scaling table: a copy of a 256 MB
array of doubles (far past every cache) with numpy, best of ten, in bytes read plus bytes written
per second. Also the same copy of arrays that fit the last-level cache (8 MB) and the core's L2
(256 kB), for the cost ratio of a working set in and out of cache.

    /usr/bin/python3 tools/bench/memory_bandwidth.py > docs/bench/memory_bandwidth.json
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


def main():
    out = {"date": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()), "cpus": os.cpu_count(),
           "load": os.getloadavg(), "method": "numpy copy b[...] = a, best of the repeats, (read + written) bytes / s"}
    for name, size, reps in (("dram_256MB", 256 << 20, 10), ("llc_8MB", 8 << 20, 200), ("l2_256kB", 256 << 10, 5000)):
        out[name + "_GBps"] = copy_rate(size, reps) / 1e9
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
