#!/usr/bin/env bash
# Alternated Google Benchmark runs of the step's kernels from two builds' bench/ folders, one thread:
# ROUNDS rounds of A then B per kernel, one CSV row per run (the benchmark's real time per iteration).
#   studies/contact/bench_kernels.sh OLD_BUILD/bench NEW_BUILD/bench > studies/contact/results/bench_kernels.csv
set -euo pipefail
a=$1 b=$2 rounds=${ROUNDS:-9}
kernels="pair_contact_bench:BM_PairForces/simd/threads:1/ wall_contact_bench:BM_WallForces/simd/threads:1/
integrate_bench:BM_KickDrift/threads:1/ integrate_bench:BM_Kick/threads:1/"
echo "round,kernel,build,seconds"
for k in $kernels; do
  prog=${k%%:*} filter=${k#*:}
  for r in $(seq 1 "$rounds"); do
    for which in A B; do
      dir=$a; [ "$which" = B ] && dir=$b
      "$dir/$prog" --benchmark_filter="$filter" --benchmark_format=csv 2>/dev/null |
        /usr/bin/python3 -c '
import csv, sys
scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
for row in csv.DictReader(l for l in sys.stdin if not l.startswith("#")):
    if row["name"].startswith("BM_"):
        name = row["name"].split("/threads")[0]
        seconds = float(row["real_time"]) * scale[row["time_unit"]]
        print(f"{sys.argv[1]},{name},{sys.argv[2]},{seconds:.6g}")
' "$r" "$which"
    done
  done
done
