#!/usr/bin/env bash
# build_fuzzers.sh — builds the libFuzzer targets (tests/fuzz/targets) with clang in
# WORK_DIR/build: ctest's fuzz_build, the set-up of fuzz_replay and fuzz_fixed_runs.
#
# Usage: build_fuzzers.sh WORK_DIR [TARGET...]      (default: every target)
# Environment: see fuzz_common.sh (FC_FUZZ_CC, FC_FUZZ_LAUNCHER, CMAKE).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/fuzz_common.sh"

fuzz_arguments fuzz_all_targets "$@"
fuzz_build "$work" "${targets[@]}"
echo "build_fuzzers.sh: built ${#targets[@]} targets in $work/build"
