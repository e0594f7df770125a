#!/usr/bin/env bash
# Where a step's time goes: the seed-000 drum, 2,000 steps on 1 thread; its summary.json (time per
# system, particle-steps/s, rebuilds) is kept as studies/performance/results/drum_time_split.json (the settled state,
# default) or studies/performance/results/drum_time_split_flowing.json (STATE=flowing: the shared state after 1.5 s).
#   [STATE=flowing] [OUT=FILE] studies/performance/time_split.sh [BUILD_DIR]   (OUT: keep the summary there instead)
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
out=$(mktemp -d)
case "${STATE:-settled}" in
  settled) scene=scenes/drum_seed000_settled.toml; keep=studies/performance/results/drum_time_split.json ;;
  flowing) scene=scenes/drum_seed000_flowing.toml; keep=studies/performance/results/drum_time_split_flowing.json ;;
  *) echo "time_split: STATE must be settled or flowing" >&2; exit 2 ;;
esac
keep=${OUT:-$keep}
"$build/grainflow" run "$scene" --steps 2000 --threads 1 --quiet --out "$out"
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)
python3 - "$out/summary.json" "$(git rev-parse --short HEAD)" "$cpu" > "$keep" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["commit"] = sys.argv[2]
s["cpu"] = sys.argv[3]
print(json.dumps(s, indent=1, sort_keys=True))
PY
rm -rf "$out"
