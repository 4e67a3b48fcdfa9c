#!/usr/bin/env bash
# build_fuzzers.sh — builds the libFuzzer targets (tests/fuzz/targets) with clang in
# WORK_DIR/build: ctest's fuzz_build, the set-up of fuzz_replay and fuzz_fixed_runs.
#
# Usage: build_fuzzers.sh WORK_DIR [TARGET...]      (default: every target)
# Environment: see fuzz_common.sh (FC_FUZZ_CC, FC_FUZZ_LAUNCHER, CMAKE).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/fuzz_common.sh"

if [[ $# -lt 1 ]]; then
    echo "usage: $0 WORK_DIR [TARGET...]" >&2
    exit 2
fi
work=$1
shift
targets=("$@")
[[ ${#targets[@]} -gt 0 ]] || targets=("${fuzz_all_targets[@]}")
fuzz_build "$work" "${targets[@]}"
echo "build_fuzzers.sh: built ${#targets[@]} targets in $work/build"
