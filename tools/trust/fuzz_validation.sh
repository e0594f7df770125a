#!/usr/bin/env bash
# The input fuzzer's validation run (100,000 inputs in 100 pieces), resumable: pieces already in
# docs/trust/fuzz/ are not run again. Usage: tools/trust/fuzz_validation.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
GRAINFLOW_FUZZ_DIR="$PWD/docs/trust/fuzz" "$build/tests/input_fuzz_validation_test"
