#!/usr/bin/env bash
# fuzz_forever.sh — open-ended fuzzing, by hand (never ctest's: what it finds depends
# on time, machine speed and luck). Builds the targets in WORK_DIR/build, then fuzzes
# each in turn for FC_FUZZ_SECONDS from a random seed, with every libFuzzer mutation,
# over WORK_DIR/corpus/<target>, which keeps growing between calls (so a later call
# starts where an earlier one stopped) and takes in the committed corpus each time.
# Fails on any crash, leak, hang or sanitizer report, printing the end of that
# target's log; the input is kept in WORK_DIR/artifacts/. Once the bug is fixed, the
# input goes into corpus/<target>/ as a regression seed (README.md, "A finding").
#
# Usage: fuzz_forever.sh WORK_DIR [TARGET...]   (default: every target but fuzz_reader_hdf5)
# Environment:
#   FC_FUZZ_SECONDS  seconds per target (default 600; 0: the first target until interrupted)
#   and fuzz_common.sh's FC_FUZZ_CC, FC_FUZZ_LAUNCHER, CMAKE
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/fuzz_common.sh"

fuzz_arguments fuzz_default_targets "$@"
seconds=${FC_FUZZ_SECONDS:-600}
fuzz_build "$work" "${targets[@]}"
mkdir -p "$work/logs"

run_target() {
    local target=$1
    local corpus=$work/corpus/$target log=$work/logs/$target.forever.log
    mkdir -p "$corpus"
    cp -n "$fuzz_dir/corpus/$target"/* "$corpus"/
    echo "fuzz_forever.sh: $target for ${seconds}s over $(ls "$corpus" | wc -l) inputs"
    if fuzz_run "$work" "$target" -max_total_time="$seconds" -print_final_stats=1 "$corpus" >"$log" 2>&1; then
        grep -E '^stat::(number_of_executed_units|new_units_added)' "$log" | tr '\n' ' '
        echo
        return 0
    fi
    fuzz_failed "$log" "$target FAILED (full log: $log, input: $work/artifacts/$target-*)"
    return 1
}

fuzz_each run_target || exit 1
echo "fuzz_forever.sh: ${#targets[@]} targets ran ${seconds}s each without a finding"
