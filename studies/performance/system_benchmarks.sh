#!/usr/bin/env bash
# The per-system benchmarks on the settled seed-000 drum (47,108 grains), at 1 and 2 threads, five
# repetitions each, as Google Benchmark JSON: studies/performance/results/<name>.json, with the machine's load and the
# commit in their context. studies/performance/system_table.py makes the README's table from them.
#   studies/performance/system_benchmarks.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
mkdir -p studies/performance/results
for b in pair_contact wall_contact broadphase integrate; do
  "$build/bench/${b}_bench" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
    --benchmark_context=commit="$(git rev-parse --short HEAD)" --benchmark_context=load="$(cut -d' ' -f1-3 /proc/loadavg)" \
    --benchmark_out="studies/performance/results/${b}.json" --benchmark_out_format=json > /dev/null
done
