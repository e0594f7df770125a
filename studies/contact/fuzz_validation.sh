#!/usr/bin/env bash
# The input fuzzer's validation run (100,000 inputs in 100 pieces), resumable: pieces already in
# studies/contact/results/fuzz/ are not run again. Two processes take a half each (each runs its scenes on
# the machine's threads as well); the last call writes summary.json over every piece written.
# Usage: studies/contact/fuzz_validation.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
dir="$PWD/studies/contact/results/fuzz"
GRAINFLOW_FUZZ_DIR="$dir" GRAINFLOW_FUZZ_PIECES=50 "$build/tests/input_fuzz_validation_test" &
GRAINFLOW_FUZZ_DIR="$dir" GRAINFLOW_FUZZ_FIRST=51 "$build/tests/input_fuzz_validation_test" &
wait
GRAINFLOW_FUZZ_DIR="$dir" GRAINFLOW_FUZZ_WRITTEN_ONLY=1 "$build/tests/input_fuzz_validation_test"
