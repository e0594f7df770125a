#!/usr/bin/env bash
# Where a step's time goes: the settled seed-000 drum, 2,000 steps on 1 thread; its summary.json (time
# per system, particle-steps/s, rebuilds) is kept as docs/bench/drum_time_split.json.
#   tools/bench/time_split.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
out=$(mktemp -d)
"$build/grainflow" run scenes/drum_seed000_settled.toml --steps 2000 --threads 1 --quiet --out "$out"
python3 - "$out/summary.json" "$(git rev-parse --short HEAD)" > docs/bench/drum_time_split.json <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["commit"] = sys.argv[2]
print(json.dumps(s, indent=1, sort_keys=True))
PY
rm -rf "$out"
