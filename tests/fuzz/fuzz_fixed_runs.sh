#!/usr/bin/env bash
# fuzz_fixed_runs.sh — fuzzes each target for a fixed number of inputs from a fixed
# random seed, starting from its committed corpus: ctest's fuzz_fixed_runs. No clock
# decides anything, so the same build gives the same verdict (and the same final
# coverage line) every time, on any machine; a new finding fails it on the change
# that made it reachable, never on an unrelated one. Open-ended fuzzing, which finds
# more but by luck, is fuzz_forever.sh's. Fails on any crash, leak, hang or sanitizer
# report, printing the end of that target's log; the input is kept in
# WORK_DIR/artifacts/.
#
# What makes a run repeatable: -seed=1 and -runs=N instead of -max_total_time; the
# seeds given in a sorted list (-seed_inputs) rather than read from a directory,
# whose order is the file system's; -reload=0; and nothing that depends on where
# address-space layout randomisation puts things: -use_cmp=0 (the operands of
# recent comparisons, which libFuzzer splices into inputs: with it on, runs of the
# readers differed between layouts) and targets built without stack-depth coverage
# (targets/CMakeLists.txt).
# Two runs with different environments were compared target by target to check it.
#
# Usage: fuzz_fixed_runs.sh WORK_DIR [TARGET...]   (default: every target but fuzz_reader_hdf5)
# Environment:
#   FC_FUZZ_RUNS  inputs run per target, the seeds included (default 25000)
# The targets must be built in WORK_DIR/build (build_fuzzers.sh).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/fuzz_common.sh"

fuzz_arguments fuzz_default_targets "$@"
runs=${FC_FUZZ_RUNS:-25000}
fuzz_require_built "$work" "${targets[@]}"
mkdir -p "$work/logs" "$work/fixed"

# The target's committed inputs as libFuzzer's comma-separated list, in byte order.
write_seed_list() {
    local target=$1
    local list=$2 seeds=() seed
    mapfile -d '' -t seeds < <(find "$fuzz_dir/corpus/$target" -maxdepth 1 -type f -print0 | LC_ALL=C sort -z)
    for seed in "${seeds[@]}"; do
        if [[ $seed == *,* ]]; then
            echo "fuzz_fixed_runs.sh: $seed has a comma in its name, which -seed_inputs cannot list" >&2
            return 1
        fi
    done
    (IFS=,; echo "${seeds[*]}") >"$list"
}

# What libFuzzer adds goes to an emptied directory of the work tree, never to the source tree.
run_target() {
    local target=$1
    local log=$work/logs/$target.fixed.log list=$work/fixed/$target.seeds corpus=$work/fixed/$target
    write_seed_list "$target" "$list" || return 1
    rm -rf "$corpus"
    mkdir -p "$corpus"
    if fuzz_run "$work" "$target" -seed=1 -runs="$runs" -seed_inputs=@"$list" -reload=0 -use_cmp=0 \
        -purge_allocator_interval=-1 -print_final_stats=1 "$corpus" >"$log" 2>&1; then
        echo "fuzz_fixed_runs.sh: $target: $(grep -m1 -E '^#[0-9]+[[:space:]]+DONE' "$log" | sed 's/ exec\/s.*//')"
        return 0
    fi
    fuzz_failed "$log" "$target FAILED (full log: $log, input: $work/artifacts/$target-*; reproduce with:
$work/build/$target -seed=1 -runs=$runs -seed_inputs=@$list $corpus)"
    return 1
}

fuzz_each run_target || exit 1
echo "fuzz_fixed_runs.sh: ${#targets[@]} targets ran $runs inputs each from seed 1 without a finding"
