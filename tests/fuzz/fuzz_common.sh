# shellcheck shell=bash
# fuzz_common.sh — sourced by the fuzz scripts (build_fuzzers.sh, replay_corpus.sh,
# fuzz_fixed_runs.sh, fuzz_forever.sh): the list of targets, their command line and their loop over
# the targets, building them with clang, and running one with the sanitizer settings every run shares.
# Environment:
#   FC_FUZZ_CC        the clang to build with (default clang-14, else clang)
#   FC_FUZZ_LAUNCHER  a compiler launcher for the build (ctest passes the suite's ccache)
#   CMAKE             the cmake to configure with (default cmake)

fuzz_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
fuzz_all_targets=(fuzz_reader_f32 fuzz_reader_ply fuzz_reader_vtk fuzz_reader_csv fuzz_reader_bgeo fuzz_reader_npy
                  fuzz_reader_vtkxml fuzz_reader_hdf5 fuzz_wire_messages fuzz_wire_session fuzz_wire_settings
                  fuzz_wire_mesh fuzz_wire_surface fuzz_srv_answer fuzz_camera_path fuzz_mesh_obj fuzz_mesh_stl fuzz_mesh_ply
                  fuzz_mesh_vtk fuzz_mesh_vtp fuzz_tls_handshake)
# fuzz_reader_hdf5 is fuzzed only when named: Debian 12's libhdf5 1.10.8 itself reads past a buffer of its own
# on some damaged compact datasets (H5VM_memcpyvv under H5Dread, found by this target in CI), which the storage
# size it reports does not reveal. Its committed corpus is replayed like every other (replay_corpus.sh).
fuzz_default_targets=()
for fuzz_t in "${fuzz_all_targets[@]}"; do
    [[ $fuzz_t == fuzz_reader_hdf5 ]] || fuzz_default_targets+=("$fuzz_t")
done
unset fuzz_t
fuzz_missing_packages="apt-get install clang-14 libclang-rt-14-dev"

fuzz_find_clang() {
    local candidate
    for candidate in ${FC_FUZZ_CC:-} clang-14 clang; do
        if command -v "$candidate" >/dev/null 2>&1; then
            command -v "$candidate"
            return 0
        fi
    done
    return 1
}

# fuzz_build WORK_DIR TARGET...: configures and builds quietly in WORK_DIR/build; on failure shows the
# log, which names the missing package.
fuzz_build() {
    local work=$1
    shift
    local cc log=$work/build.log
    cc=$(fuzz_find_clang) || {
        echo "clang not found; the fuzz targets need clang with libFuzzer: $fuzz_missing_packages" >&2
        return 1
    }
    local configure=(-S "$fuzz_dir/targets" -B "$work/build" -DCMAKE_C_COMPILER="$cc")
    [[ -n ${FC_FUZZ_LAUNCHER:-} ]] && configure+=(-DCMAKE_C_COMPILER_LAUNCHER="$FC_FUZZ_LAUNCHER")
    mkdir -p "$work"
    if ! "${CMAKE:-cmake}" "${configure[@]}" >"$log" 2>&1 ||
        ! "${CMAKE:-cmake}" --build "$work/build" -j2 --target "$@" >>"$log" 2>&1; then
        cat "$log" >&2
        echo "building the fuzz targets failed (see above; clang and libFuzzer come from: $fuzz_missing_packages)" >&2
        return 1
    fi
}

# fuzz_require_built WORK_DIR TARGET...: fails naming the build step when a target is not there.
fuzz_require_built() {
    local work=$1 target
    shift
    for target in "$@"; do
        if [[ ! -x $work/build/$target ]]; then
            echo "$work/build/$target is not built: run tests/fuzz/build_fuzzers.sh $work first" >&2
            return 1
        fi
    done
}

# fuzz_run WORK_DIR TARGET LIBFUZZER_ARGUMENT...: runs the target with the sanitizer settings and the
# options every run shares; its exit status is libFuzzer's (0: no finding).
# -timeout is a hang detector, generous so that a loaded machine does not turn a slow input into a
# finding. -reload=0: the corpus is re-read only when another process could have added to it.
fuzz_run() {
    local work=$1 target=$2
    shift 2
    local options=(-rss_limit_mb=2048 -timeout=120 -artifact_prefix="$work/artifacts/$target-")
    [[ -f $fuzz_dir/dict/$target.dict ]] && options+=(-dict="$fuzz_dir/dict/$target.dict")
    local asan=detect_leaks=1
    # libhdf5 (not ours, not instrumented) sizes its metadata buffers from the file: a damaged size asks
    # malloc for terabytes, which it answers NULL and refuses the file. Our readers bound every
    # allocation by the file's size themselves, so only this target lets such a malloc fail.
    if [[ $target == fuzz_reader_hdf5 ]]; then
        asan=$asan:allocator_may_return_null=1
        options+=(-malloc_limit_mb=1048576)
    fi
    mkdir -p "$work/artifacts"
    # Leaks inside third-party libraries are listed, with why, in ../sanitizer/lsan.supp.
    ASAN_OPTIONS=$asan UBSAN_OPTIONS=print_stacktrace=1 \
        LSAN_OPTIONS="suppressions=$fuzz_dir/../sanitizer/lsan.supp:print_suppressions=0" \
        "$work/build/$target" "${options[@]}" "$@"
}

# fuzz_arguments DEFAULT_LIST ARG...: a script's command line, WORK_DIR [TARGET...]: sets `work`
# and `targets` (the targets named, else the array called DEFAULT_LIST); the usage and exit 2 without
# WORK_DIR.
fuzz_arguments() {
    local -n fuzz_defaults=$1
    shift
    if [[ $# -lt 1 ]]; then
        echo "usage: $0 WORK_DIR [TARGET...]" >&2
        exit 2
    fi
    work=$1
    shift
    if [[ $# -gt 0 ]]; then
        targets=("$@")
    else
        targets=("${fuzz_defaults[@]}")
    fi
}

# fuzz_failed LOG MESSAGE: the end of a failed run's log, then what failed, on stderr.
fuzz_failed() {
    tail -n 80 "$1" >&2
    echo "$(basename "$0"): $2" >&2
}

# fuzz_each FUNCTION: FUNCTION TARGET for every one of `targets`, going on past a failure; fails
# naming every target that failed.
fuzz_each() {
    local run=$1 target failed=()
    for target in "${targets[@]}"; do
        "$run" "$target" || failed+=("$target")
    done
    if [[ ${#failed[@]} -gt 0 ]]; then
        echo "$(basename "$0"): failing targets: ${failed[*]}" >&2
        return 1
    fi
}
