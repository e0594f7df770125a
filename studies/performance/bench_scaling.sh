#!/usr/bin/env bash
# Cost against grain count: particle-steps/s of whole steps on scenes/bench/settled_layer.toml with
# 1e4, 1e5 and 1e6 grains (the layer widened; same depth and physics per column), at 1 and 2
# threads, after the layer has settled (untimed). Linear cost shows as equal particle-steps/s.
#   studies/performance/bench_scaling.sh [BUILD_DIR]      (environment: SIZES="0.0418 0.1321 0.4178", STEPS=200, THREADS=1,2)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
BUILD="${1:-$REPO/build}"
SIZES="${SIZES:-0.0418 0.1321 0.4178}"
STEPS="${STEPS:-200}"
THREADS="${THREADS:-1,2}"
echo "# bench_scaling: $(date -u +%Y-%m-%dT%H:%M:%SZ), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), repo $(git -C "$REPO" rev-parse --short HEAD)"
for L in $SIZES; do
  sets=(--set="wall.0.hi=[$L,0.012,$L]" --set="fill.0.region.hi=[$L,0.012,$L]")
  echo "L=$L m  $("$BUILD/grainflow" check "$REPO/scenes/bench/settled_layer.toml" --set "wall.0.hi=[$L,0.012,$L]" \
    --set "fill.0.region.hi=[$L,0.012,$L]" | grep -E 'memory estimate')"
  "$BUILD/bench/end_to_end_bench" --scene="$REPO/scenes/bench/settled_layer.toml" --settle --steps="$STEPS" \
    "${sets[@]}" --threads="$THREADS" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true 2>&1 |
    grep -E "median" | sed "s/^/L=$L m  /"
done
