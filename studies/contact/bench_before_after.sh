#!/usr/bin/env bash
# Alternated end-to-end throughput of two grainflow builds on one scene: ROUNDS rounds of
# A then B at each thread count, particle-steps/s from each run's summary.json, one CSV row per run.
#   studies/contact/bench_before_after.sh OLD_BINARY NEW_BINARY [SCENE] [STEPS] > studies/contact/results/bench_before_after.csv
set -euo pipefail
a=$1 b=$2 scene=${3:-scenes/drum_seed000_settled.toml} steps=${4:-2000}
rounds=${ROUNDS:-5} threads=${THREADS:-"1 2"} extra=${EXTRA:-}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "round,threads,build,particle_steps_per_s"
for r in $(seq 1 "$rounds"); do
  for t in $threads; do
    for which in A B; do
      bin=$a; [ "$which" = B ] && bin=$b
      # shellcheck disable=SC2086
      "$bin" run "$scene" --steps "$steps" --threads "$t" --quiet --out "$out/run" $extra > /dev/null 2>&1
      rate=$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["particle_steps_per_second"])' "$out/run/summary.json")
      echo "$r,$t,$which,$rate"
    done
  done
done
