#!/usr/bin/env bash
# Is algebraic multigrid worth it for the liquid's pressure solve? Writes the pressure Poisson system of
# the 1e5-node 3D still tank (bench/mps_tank.hpp, side 46) and solves it with grainflow's Jacobi CG (1 and
# 2 threads) and with hypre's PCG + BoomerAMG under several settings (1 and 2 OpenMP threads), each to the
# relative residual 1e-8 from p = 0; one JSON object per line into docs/liquid/amg_probe.jsonl, then the
# README's table (tools/readme/tables.py amg_probe). hypre is not a dependency of grainflow (Debian
# builds it with MPI, which the single-process program does not link): this probe needs
#   apt-get install -y libhypre-dev
# and a built tree (cmake --build build). Run it with both cores free.
#   tools/liquid/amg_probe.sh [BUILD_DIR] [REPEATS]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
repeats=${2:-5}
[ -f /usr/include/hypre/HYPRE.h ] || { echo "amg_probe: hypre not found (apt-get install -y libhypre-dev)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
src=tools/liquid/amg_probe
g++ -O2 -march=native -std=c++20 -I. -I/usr/include/eigen3 "$src/dump_ppe.cpp" -o "$work/dump_ppe" \
  "$build/libgrainflow_core.a" -ltbb -lpng -lccd -ltomlplusplus -lpthread
mpicxx -O2 -march=native -std=c++17 -I/usr/include/hypre "$src/hypre_pcg.cpp" -o "$work/hypre_pcg" -lHYPRE
out=docs/liquid/amg_probe.jsonl
{
  echo "{\"commit\": \"$(git rev-parse --short HEAD)\", \"date\": \"$(date -u +%Y-%m-%dT%H:%M:%SZ)\", \"repeats\": $repeats, \"tank\": \"3D still tank, side 46, l0 5 mm\"}"
  "$work/dump_ppe" 46 "$work/A.bin" "$repeats"
  for threads in 1 2; do
    for opts in "10 0.5 6 0 4 6" "10 0.5 6 1 4 6" "10 0.5 6 1 4 18" "10 0.5 6 1 4 8" "10 0.8 6 1 2 6" "8 0.8 6 1 2 6" "10 0.5 13 1 4 18"; do
      OMP_NUM_THREADS=$threads "$work/hypre_pcg" "$work/A.bin" "$repeats" $opts
    done
  done
} > "$out"
echo "amg_probe: $out" >&2
