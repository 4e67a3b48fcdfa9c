#!/usr/bin/env bash
# replay_corpus.sh — runs every committed input of corpus/<target>/ (the seeds and the
# regress_* inputs that once found a bug) through its target once, no mutation:
# ctest's fuzz_replay. The same build gives the same verdict every time. Fails on
# any crash, leak, hang or sanitizer report, printing the end of that target's log,
# which names the input ("Running: ...").
#
# Usage: replay_corpus.sh WORK_DIR [TARGET...]   (default: every target, fuzz_reader_hdf5 too)
# The targets must be built in WORK_DIR/build (build_fuzzers.sh).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/fuzz_common.sh"

fuzz_arguments fuzz_all_targets "$@"
fuzz_require_built "$work" "${targets[@]}"
mkdir -p "$work/logs"

# libFuzzer given files (not a directory) runs each once and exits.
replay_target() {
    local target=$1
    local log=$work/logs/$target.replay.log
    local inputs=("$fuzz_dir/corpus/$target"/*)
    if [[ ! -f ${inputs[0]} ]]; then
        echo "replay_corpus.sh: corpus/$target/ has no input" >&2
        return 1
    fi
    if fuzz_run "$work" "$target" "${inputs[@]}" >"$log" 2>&1; then
        echo "replay_corpus.sh: $target: ${#inputs[@]} inputs"
        return 0
    fi
    fuzz_failed "$log" "$target FAILED on a committed input (full log: $log)"
    return 1
}

fuzz_each replay_target || exit 1
echo "replay_corpus.sh: every committed input of ${#targets[@]} targets passed"
