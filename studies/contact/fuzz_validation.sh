#!/usr/bin/env bash
# The input fuzzer's validation run (100,000 inputs in 100 pieces), resumable: pieces already in
# studies/contact/results/fuzz/ are not run again. Usage: studies/contact/fuzz_validation.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
GRAINFLOW_FUZZ_DIR="$PWD/studies/contact/results/fuzz" "$build/tests/input_fuzz_validation_test"
