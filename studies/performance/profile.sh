#!/usr/bin/env bash
# Where the flowing drum's step spends its cycles, by function: perf record of 2,000 steps of
# scenes/drum_seed000_flowing.toml on 1 thread, the top functions (self time, names shortened to the
# kernel they belong to) written to studies/performance/results/profile_flowing.txt. Needs perf (apt-get install
# linux-perf); the README table is made from that file by studies/performance/profile_table.py.
#   [OUT=studies/performance/results/profile_flowing.txt] studies/performance/profile.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
keep=${OUT:-studies/performance/results/profile_flowing.txt}
command -v perf >/dev/null || { echo "profile: perf not found (apt-get install linux-perf)" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
perf record -q -o "$out/perf.data" "$build/grainflow" run scenes/drum_seed000_flowing.toml --steps 2000 --threads 1 \
  --quiet --out "$out/run" 2> /dev/null
{
  echo "# perf record, scenes/drum_seed000_flowing.toml, 2000 steps, 1 thread, commit $(git rev-parse --short HEAD), $(date -u +%Y-%m-%dT%H:%M:%SZ), $(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)"
  echo "# self % | function (perf report --no-children, symbols as perf prints them)"
  perf report -i "$out/perf.data" --no-children --stdio -g none > "$out/report.txt" 2> /dev/null
  grep -E '^ +[0-9]' "$out/report.txt" | awk 'NR <= 40 {pct=$1; $1=$2=$3=$4=""; sub(/^ +/, ""); print pct " | " $0}'
} > "$keep"
echo "profile: $keep" >&2
