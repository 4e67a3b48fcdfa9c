#!/usr/bin/env bash
# gpu_check.sh — what to run the moment an NVIDIA GPU is lent (issue 12): the render test
# suite on the GPU through EGL's device platform, then the PNG writer on the host's cores
# (fluidcast-png-bench, some seconds), then bench/run_targets.sh, into one report. Under 8 minutes, and it needs nothing but a built tree and the runtime libraries.
#
#   bench/gpu_check.sh --prepare     # here: a slim Release tree in build-gpu (what to carry)
#   bench/gpu_check.sh [REPORT]      # there: runs; REPORT defaults to $OUT/gpu-report.md
#                                    # when $OUT is set, else ./gpu-report.md
#
# The device tool's run carries the tree: run with carry ["build-gpu"] and the command
# `bench/gpu_check.sh`. The tree's paths may differ there: the tests' ctest files are
# rewritten to the new root (a copy; the tests find their data by those paths) and
# nothing is rebuilt (NO_BUILD=1 for run_targets.sh).
#
# The render tests take their device from FC_TEST_GPU (tests/render/render_fixture.h):
# GPU=auto (default) is the EGL device platform's first GPU, GPU=N device N,
# GPU=software llvmpipe (to try the script on a machine without a GPU).
#
# Environment: BUILD_DIR (default build-gpu), GPU, TEST_BUDGET (seconds for the tests,
# default 240), TARGETS_BUDGET (seconds for run_targets.sh, default 200), TEST_JOBS (4).
set -uo pipefail
scratch=""

ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD_DIR=${BUILD_DIR:-$ROOT/build-gpu}
case $BUILD_DIR in /*) ;; *) BUILD_DIR=$ROOT/$BUILD_DIR ;; esac
GPU=${GPU:-auto}
TEST_BUDGET=${TEST_BUDGET:-240}
TARGETS_BUDGET=${TARGETS_BUDGET:-200}
TEST_JOBS=${TEST_JOBS:-4}
BENCH_PROGRAMS=(fluidcast-bench fluidcast-e2e-bench fluidcastd fluidcast-png-bench fluidcast-mesh-bench)

log() { echo "gpu_check: $*" >&2; }

# The render test programs the build defines (test_render_*, test_shading_*, test_smoothing_*).
render_test_targets() {
    cmake --build "$BUILD_DIR" --target help | awk '{ print $2 }' | grep -E '^test_(render|shading|smoothing)_' || true
}

prepare() {
    cmake -S "$ROOT" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release >/dev/null || exit 1
    local targets
    targets=$(render_test_targets) || exit 1
    # shellcheck disable=SC2086
    cmake --build "$BUILD_DIR" -j"$(nproc)" --target ${targets} "${BENCH_PROGRAMS[@]}" || exit 1
    log "built $(echo "$targets" | wc -w) render test programs and ${BENCH_PROGRAMS[*]}: $(du -sh "$BUILD_DIR" | cut -f1)"
}

# A carried tree names the machine it was built on: point its ctest files at this one.
relocate() {
    local old_root old_build
    old_root=$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$BUILD_DIR/CMakeCache.txt")
    old_build=$(sed -n 's/^CMAKE_CACHEFILE_DIR:INTERNAL=//p' "$BUILD_DIR/CMakeCache.txt")
    [ -n "$old_root" ] && [ -n "$old_build" ] || { log "no CMakeCache.txt in $BUILD_DIR"; return 1; }
    [ "$old_build" = "$BUILD_DIR" ] && [ "$old_root" = "$ROOT" ] && return 0
    log "tree built at $old_build for $old_root: its ctest files now point at $BUILD_DIR and $ROOT"
    find "$BUILD_DIR" -name CTestTestfile.cmake -print0 |
        xargs -0 sed -i -e "s#$old_build#$BUILD_DIR#g" -e "s#$old_root#$ROOT#g"
}

device_lines() {
    echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC'); git: $(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo '?')"
    echo "- load average at start: $(cut -d' ' -f1-3 /proc/loadavg); $(nproc) cores"
    if command -v nvidia-smi >/dev/null; then
        echo "- nvidia-smi: $(nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2>&1 | head -n 3 | tr '\n' ';')"
    else
        echo "- nvidia-smi: not installed"
    fi
    echo "- EGL vendors: $(ls /usr/share/glvnd/egl_vendor.d/ 2>/dev/null | tr '\n' ' ')"
    local missing
    missing=$(ldd "$BUILD_DIR/bin/fluidcast-bench" 2>/dev/null | grep 'not found' | awk '{ print $1 }' | tr '\n' ' ')
    echo "- libraries missing for fluidcast-bench: ${missing:-none}"
    # The device the tests will get, as fluidcast-bench reports it (its first line).
    echo "- GPU=$GPU renders on: $(timeout 60 "$BUILD_DIR/bin/fluidcast-bench" --gpu "$GPU" --particles 4096 \
        --size 64x64 --frames 1 --encode none 2>&1 | head -n 1)"
}

run_tests() {
    local log_file=$1 summary
    echo "## Render tests on GPU=$GPU (FC_TEST_GPU), ctest -R '^render_'"
    echo
    FC_TEST_GPU=$GPU timeout "$TEST_BUDGET" ctest --test-dir "$BUILD_DIR" -R '^render_' \
        -E 'render_shaders_glslang' -j "$TEST_JOBS" --timeout 120 --output-on-failure >"$log_file" 2>&1
    local rc=$?
    [ $rc -eq 124 ] && echo "- stopped after TEST_BUDGET=${TEST_BUDGET}s"
    summary=$(grep -E 'tests passed|tests failed' "$log_file" | tail -n 1)
    echo "- ${summary:-no summary (exit $rc)}"
    echo
    grep -E '^ *[0-9]+/[0-9]+ Test +#' "$log_file" | sed -E 's/^ *[0-9]+\/[0-9]+ Test +#[0-9]+: /    /'
    echo
    if grep -q 'Failed\|\*\*\*' "$log_file"; then
        echo "Failures (output):"
        echo
        grep -B2 -A25 -E 'CHECK failed|\*\*\*Failed|\*\*\*Exception|Timeout' "$log_file" | head -n 200 | sed 's/^/    /'
        echo
    fi
}

# The daemon's PNG writer on this host's cores: the encoder is the whole cost once the
# render takes milliseconds. bench/peer/fluidcast.png is a real render (1280x720 RGBA).
run_png_bench() {
    echo "## PNG encoding on $(nproc) cores (fluidcast-png-bench, bench/peer/fluidcast.png)"
    echo
    timeout 60 "$BUILD_DIR/bin/fluidcast-png-bench" --threads 1,2,4,8,0 --level 1,4 --rounds 9 \
        "$ROOT/bench/peer/fluidcast.png" 2>&1 || echo "- fluidcast-png-bench exit $?"
    echo
}

# Surface mesh extraction (issue 27) on the GPU: particles meshed per second by cell size.
run_mesh_bench() {
    echo "## Surface mesh extraction (fluidcast-mesh-bench)"
    echo
    timeout 90 "$BUILD_DIR/bin/fluidcast-mesh-bench" --gpu "$GPU" --particles 65536,1048576 --cells 0.5,1,1.5 \
        --repeat 3 2>&1 || echo "- fluidcast-mesh-bench exit $?"
    echo
}

main() {
    if [ "${1:-}" = "--prepare" ]; then
        prepare
        return
    fi
    local report=${1:-${OUT:+$OUT/gpu-report.md}}
    report=${report:-$PWD/gpu-report.md}
    scratch=$(mktemp -d)
    trap 'rm -rf "$scratch"' EXIT
    relocate || exit 1
    {
        echo "# GPU check (bench/gpu_check.sh)"
        echo
        device_lines
        echo
        run_tests "$scratch/tests.log"
        run_png_bench
        run_mesh_bench
    } >"$report"
    [ -n "${OUT:-}" ] && cp "$scratch/tests.log" "$OUT/gpu-tests.log" 2>/dev/null
    log "tests done: $(grep -E 'tests passed|tests failed' "$scratch/tests.log" | tail -n 1)"
    # Each of its three steps gets a third of the budget, so a slow one fails alone and the
    # report still has the others; the outer limit only catches a hang between steps.
    BUILD_DIR=$BUILD_DIR GPU=$GPU NO_BUILD=1 STEP_TIMEOUT=$((TARGETS_BUDGET / 3)) \
        timeout $((TARGETS_BUDGET + 30)) "$ROOT/bench/run_targets.sh" >>"$report" 2>"$scratch/targets.log"
    local rc=$?
    if [ $rc -ne 0 ]; then
        { echo; echo "run_targets.sh exit $rc (TARGETS_BUDGET=${TARGETS_BUDGET}s):"; } >>"$report"
    fi
    { echo; echo "run_targets.sh's log:"; echo; sed 's/^/    /' "$scratch/targets.log"; } >>"$report"
    log "report: $report"
}

main "$@"
