#!/usr/bin/env bash
# Peak memory of a drum run (the settled seed-000 drum, 200 steps, 2 threads, with its series, pictures
# and end checkpoint), as /usr/bin/time reports it: studies/performance/results/memory.log.
#   studies/performance/memory.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
out=$(mktemp -d)
{
  echo "# commit $(git rev-parse --short HEAD), $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "# /usr/bin/time -f 'peak_rss_kb %M' $build/grainflow run scenes/drum_seed000_settled.toml --steps 200 --threads 2 --quiet"
  /usr/bin/time -f 'peak_rss_kb %M' "$build/grainflow" run scenes/drum_seed000_settled.toml --steps 200 --threads 2 \
    --quiet --out "$out" 2>&1 | grep peak_rss_kb
  echo "grains $(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['grains'])" "$out/summary.json")"
} > studies/performance/results/memory.log
rm -rf "$out"
