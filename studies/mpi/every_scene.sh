#!/bin/bash
# Every scene under scenes/ on two ranks for a few steps, as a user starts it (mpirun -np 2
# build/grainflow run SCENE, which hands the ranks over to grainflow_mpi) (settling skipped where the scene has a
# [settle] table): the run's exit status and its last line, into studies/mpi/results/every_scene.csv. DEM
# scenes of spheres and of composite bodies must complete; liquid scenes are refused with the reason.
#   studies/mpi/every_scene.sh [STEPS]      (from the repository root, after the build)
cd "$(dirname "$0")/../.." || exit 2
steps=${1:-20}
out=studies/mpi/results/every_scene.csv
work=$(mktemp -d)
echo "scene,kind,exit_status,seconds,last_line" > $out
for s in scenes/*.toml scenes/tests/*.toml scenes/liquid/*.toml; do
  kind=spheres
  grep -q '^\[\[bodies\]\]' "$s" && kind=bodies
  grep -q '^\[liquid\]' "$s" && kind=liquid
  extra=()
  grep -q '^\[settle\]' "$s" && extra=(--set settle.time=0)
  t0=$(date +%s.%N)
  log=$(timeout 600 mpirun --allow-run-as-root --oversubscribe -np 2 build/grainflow run "$s" \
        --out "$work/$(basename "$s" .toml)" --steps "$steps" --threads 1 --quiet "${extra[@]}" 2>&1)
  rc=$?
  t1=$(date +%s.%N)
  last=$(printf '%s\n' "$log" | grep -E '^grainflow(_mpi)?: .*(steps in | after [0-9]+ steps| key |error)' | tail -1 | tr -d '",' | cut -c1-200)
  last=${last//$work/DIR}
  printf '%s,%s,%d,%.1f,"%s"\n' "$s" "$kind" "$rc" "$(echo "$t1 - $t0" | bc)" "$last" | tee -a $out
done
rm -rf "$work"
