#!/usr/bin/env bash
# run_fuzzers.sh — builds the libFuzzer targets (tests/fuzz/targets) with clang in
# WORK_DIR/build, then runs each over a fresh copy of its seed corpus for a
# bounded time. Fails on any crash, leak, timeout or sanitizer report, printing
# the end of that target's log; the input that caused it is kept in
# WORK_DIR/artifacts/.
#
# Usage: run_fuzzers.sh WORK_DIR [TARGET...]      (default: every target)
# Environment:
#   FC_FUZZ_SECONDS  total fuzzing time, split evenly between the targets (default 120)
#   FC_FUZZ_CC       the clang to build with (default clang-14, else clang)
#   CMAKE            the cmake to configure with (default cmake)
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
all_targets=(fuzz_reader_f32 fuzz_reader_ply fuzz_reader_vtk fuzz_reader_csv fuzz_reader_bgeo fuzz_reader_npy fuzz_reader_vtkxml fuzz_reader_hdf5 fuzz_wire_messages fuzz_wire_session
             fuzz_wire_settings fuzz_wire_mesh fuzz_srv_answer fuzz_camera_path fuzz_mesh_obj fuzz_mesh_stl fuzz_mesh_ply
             fuzz_mesh_vtk fuzz_mesh_vtp)
missing_packages="apt-get install clang-14 libclang-rt-14-dev"

if [[ $# -lt 1 ]]; then
    echo "usage: $0 WORK_DIR [TARGET...]" >&2
    exit 2
fi
work=$1
shift
targets=("$@")
# fuzz_reader_hdf5 runs only when named: Debian 12's libhdf5 1.10.8 itself reads past a buffer of its own on
# some damaged compact datasets (H5VM_memcpyvv under H5Dread, found by this target in CI), which the storage
# size it reports does not reveal; a bounded run in CI would fail at random on libhdf5's bug, not ours.
default_targets=()
for t in "${all_targets[@]}"; do [[ $t == fuzz_reader_hdf5 ]] || default_targets+=("$t"); done
[[ ${#targets[@]} -gt 0 ]] || targets=("${default_targets[@]}")
total_seconds=${FC_FUZZ_SECONDS:-120}
cmake_command=${CMAKE:-cmake}

find_clang() {
    local candidate
    for candidate in ${FC_FUZZ_CC:-} clang-14 clang; do
        if command -v "$candidate" >/dev/null 2>&1; then
            command -v "$candidate"
            return 0
        fi
    done
    return 1
}

# Configures and builds quietly; on failure shows the log, which names the missing package.
build_targets() {
    local cc=$1 log=$work/build.log
    if ! "$cmake_command" -S "$here/targets" -B "$work/build" -DCMAKE_C_COMPILER="$cc" >"$log" 2>&1 ||
        ! "$cmake_command" --build "$work/build" -j2 --target "${targets[@]}" >>"$log" 2>&1; then
        cat "$log" >&2
        echo "run_fuzzers.sh: building the fuzz targets failed (see above; clang and libFuzzer come from: $missing_packages)" >&2
        return 1
    fi
}

# Runs one target over a copy of its seeds, so that what libFuzzer adds never lands in the source tree.
run_target() {
    local target=$1 seconds=$2
    local corpus=$work/corpus/$target log=$work/logs/$target.log
    local options=(-max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1
                   -artifact_prefix="$work/artifacts/$target-")
    [[ -f $here/dict/$target.dict ]] && options+=(-dict="$here/dict/$target.dict")
    local asan=detect_leaks=1
    # libhdf5 (not ours, not instrumented) sizes its metadata buffers from the file: a damaged size asks
    # malloc for terabytes, which it answers NULL and refuses the file. Our readers bound every
    # allocation by the file's size themselves, so only this target lets such a malloc fail.
    if [[ $target == fuzz_reader_hdf5 ]]; then
        asan=$asan:allocator_may_return_null=1
        options+=(-malloc_limit_mb=1048576)
    fi
    rm -rf "$corpus"
    mkdir -p "$corpus"
    cp "$here/corpus/$target"/* "$corpus"/
    echo "run_fuzzers.sh: $target for ${seconds}s over $(ls "$corpus" | wc -l) seeds"
    # Leaks inside third-party libraries are listed, with why, in ../sanitizer/lsan.supp.
    if ASAN_OPTIONS=$asan UBSAN_OPTIONS=print_stacktrace=1 \
        LSAN_OPTIONS="suppressions=$here/../sanitizer/lsan.supp:print_suppressions=0" \
        "$work/build/$target" "${options[@]}" "$corpus" >"$log" 2>&1; then
        grep -E '^stat::(number_of_executed_units|new_units_added)' "$log" | tr '\n' ' '
        echo
        return 0
    fi
    tail -n 80 "$log" >&2
    echo "run_fuzzers.sh: $target FAILED (full log: $log, input: $work/artifacts/$target-*)" >&2
    return 1
}

cc=$(find_clang) || {
    echo "run_fuzzers.sh: clang not found; the fuzz targets need clang with libFuzzer: $missing_packages" >&2
    exit 1
}
mkdir -p "$work/logs" "$work/artifacts"
build_targets "$cc"

seconds_each=$((total_seconds / ${#targets[@]}))
[[ $seconds_each -ge 1 ]] || seconds_each=1
failed=()
for target in "${targets[@]}"; do
    run_target "$target" "$seconds_each" || failed+=("$target")
done
if [[ ${#failed[@]} -gt 0 ]]; then
    echo "run_fuzzers.sh: failing targets: ${failed[*]}" >&2
    exit 1
fi
echo "run_fuzzers.sh: all ${#targets[@]} targets ran ${seconds_each}s each without a finding"
