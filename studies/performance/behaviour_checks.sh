#!/bin/bash
# Whether a change of the program's structure left what users get unchanged: two builds' grainflow and
# grainflow_mpi (BEFORE_DIR, AFTER_DIR) run alike and their files compared byte for byte.
#
#   bash studies/performance/behaviour_checks.sh BEFORE_DIR AFTER_DIR LOG
#
# Checks, each a line "PASS name" or "FAIL name: why" in LOG (and the exit status the count of FAILs):
#   - drum_quick's series.csv and final_state.csv, before against after (one thread), and after on one
#     thread against after on two;
#   - a checkpoint the BEFORE build wrote (drum_quick at step 20000; a 3D dam break at step 150)
#     resumed by the AFTER build, against the BEFORE build's uninterrupted run;
#   - every file but summary.json and the checkpoints of a composite-grain hopper (2000 steps), a mixed
#     hopper of bodies and spheres, a liquid and a liquid with grains, and drum_quick on two MPI ranks;
#   - summary.json: every key the BEFORE build wrote is still written.
set -u
before=$(realpath "$1") after=$(realpath "$2") log=$3
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
say() { echo "$1" | tee -a "$log"; }
check() {  # name, then a command whose success is the check
  local name=$1; shift
  if "$@" >"$work/why" 2>&1; then say "PASS $name"; else say "FAIL $name: $(head -c 300 "$work/why")"; fails=$((fails + 1)); fi
}
run() {  # build, output folder, scene and options
  local build=$1 out=$2 scene=$3; shift 3
  "$build/grainflow" run "$root/$scene" --quiet --out "$out" "$@" >/dev/null 2>&1
}
ranks() {
  local build=$1 out=$2 scene=$3; shift 3
  mpiexec --allow-run-as-root --oversubscribe -n 2 "$build/grainflow_mpi" run "$root/$scene" --out "$out" "$@" >/dev/null 2>&1
}
same_files() {  # every file of $1 but summary.json and checkpoints also in $2, byte for byte
  local a=$1 b=$2 f
  (cd "$a" && find . -type f ! -name summary.json ! -path './checkpoints/*' | sort) >"$work/files"
  [ -s "$work/files" ] || { echo "no files in $a"; return 1; }
  while read -r f; do cmp "$a/$f" "$b/$f" || return 1; done <"$work/files"
}
same_keys() {  # every key of $1/summary.json also in $2/summary.json
  python3 -c "import json,sys; a=json.load(open(sys.argv[1])); b=json.load(open(sys.argv[2])); m=sorted(set(a)-set(b)); print('missing:', m); sys.exit(1 if m else 0)" "$1/summary.json" "$2/summary.json"
}

: >"$log"
say "# behaviour checks: before $(cat "$before/commit" 2>/dev/null || echo "$before"), after $(cat "$after/commit" 2>/dev/null || echo "$after"), $(date -u +%Y-%m-%dT%H:%MZ)"
run "$before" "$work/dq_b" scenes/drum_quick.toml --threads 1
run "$after" "$work/dq_a" scenes/drum_quick.toml --threads 1
run "$after" "$work/dq_a2" scenes/drum_quick.toml --threads 2
check "drum_quick series.csv, before = after" cmp "$work/dq_b/series.csv" "$work/dq_a/series.csv"
check "drum_quick final_state.csv, before = after" cmp "$work/dq_b/final_state.csv" "$work/dq_a/final_state.csv"
check "drum_quick series.csv, 1 thread = 2 threads" cmp "$work/dq_a/series.csv" "$work/dq_a2/series.csv"
check "drum_quick summary keys kept" same_keys "$work/dq_b" "$work/dq_a"

run "$before" "$work/old" scenes/drum_quick.toml --threads 1 --steps 20000
run "$after" "$work/old" scenes/drum_quick.toml --threads 1 --resume "$work/old/checkpoints/checkpoint.gfc"
check "drum_quick: a checkpoint written before resumes bit for bit" cmp "$work/old/series.csv" "$work/dq_b/series.csv"
run "$before" "$work/liq_full" scenes/liquid/dam_break_3d.toml --steps 300
run "$before" "$work/liq_old" scenes/liquid/dam_break_3d.toml --steps 150
run "$after" "$work/liq_old" scenes/liquid/dam_break_3d.toml --steps 300 --resume "$work/liq_old/checkpoints/checkpoint.gfc"
check "dam break: a checkpoint written before resumes bit for bit" cmp "$work/liq_old/series.csv" "$work/liq_full/series.csv"

while read -r name scene opts; do
  # shellcheck disable=SC2086
  run "$before" "$work/${name}_b" "$scene" $opts
  # shellcheck disable=SC2086
  run "$after" "$work/${name}_a" "$scene" $opts
  check "$name: every output file, before = after" same_files "$work/${name}_b" "$work/${name}_a"
  check "$name: summary keys kept" same_keys "$work/${name}_b" "$work/${name}_a"
done <<'EOF'
hopper scenes/hopper_seed002_cost.toml --steps 2000 --threads 1
mixed_hopper scenes/hopper_mixed_prisms_spheres.toml --steps 300 --threads 1 --set settle.time=0.01
dam_break scenes/liquid/dam_break_3d.toml --steps 300
fluidised_bed scenes/liquid/fluidised_bed.toml --steps 100
EOF
ranks "$before" "$work/r2_b" scenes/drum_quick.toml --steps 20000 --threads 1
ranks "$after" "$work/r2_a" scenes/drum_quick.toml --steps 20000 --threads 1
check "drum_quick on 2 ranks: every output file, before = after" same_files "$work/r2_b" "$work/r2_a"
check "drum_quick on 2 ranks: summary keys kept" same_keys "$work/r2_b" "$work/r2_a"
say "# $fails failed"
exit "$fails"
