#!/usr/bin/env bash
# run_targets.sh — the issue's GPU targets, measured on whatever GL device this machine
# has, each next to its target:
#   1. 1M particles at 1920x1080, curvature flow (40 iterations, 1/2 resolution), thickness
#      and compositing: GPU time, the sum of the stages' timer queries (readback included),
#      <= 2 ms;
#   2. the same with 16M particles: <= 20 ms;
#   3. a producer streaming 1M-particle frames to a viewer over loopback through a real
#      fluidcastd, 1920x1080 JPEG: >= 120 images per second at the viewer.
#
#   bench/run_targets.sh > targets-report.md
#
# The targets are an NVIDIA H200's: with GPU=auto (the default) fluidcast-bench and the
# daemon take the EGL device platform's GPU when there is one, else Mesa llvmpipe, where
# the report shows how far a CPU renderer is from them. Builds fluidcast-bench,
# fluidcast-e2e-bench and fluidcastd (Release, in $BUILD_DIR, default build-bench).
#
# Environment: BUILD_DIR; NO_BUILD=1 (the programs in BUILD_DIR as built, nothing rebuilt);
# GPU (auto or software); FRAMES (timed frames for 1M particles,
# default 5), LARGE_FRAMES (for 16M, default 3), STREAM_SECONDS (default 10), STEP_TIMEOUT
# (seconds one step may take, default 600). On 2 cores with llvmpipe it takes about two
# minutes.
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD_DIR=${BUILD_DIR:-$ROOT/build-bench}
GPU=${GPU:-auto}
FRAMES=${FRAMES:-5}
LARGE_FRAMES=${LARGE_FRAMES:-3}
STREAM_SECONDS=${STREAM_SECONDS:-10}
STEP_TIMEOUT=${STEP_TIMEOUT:-600}
SIZE=1920x1080
RENDER_ARGS=(--size "$SIZE" --smoothing curvature --iterations 40 --scale 0.5 --encode none)

WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

log() { echo "run_targets: $*" >&2; }
. "$ROOT/bench/bench_lib.sh"

table_rows() { grep '^| [0-9]' || true; }

# fluidcast-bench for one particle count: its table rows into $WORK/render.md.
render_step() {
    local particles=$1 frames=$2 args
    args=(--gpu "$GPU" --particles "$particles" --frames "$frames" "${RENDER_ARGS[@]}")
    echo "fluidcast-bench ${args[*]}" >>"$WORK/commands"
    log "fluidcast-bench ${args[*]}"
    timeout "$STEP_TIMEOUT" "$BUILD_DIR/bin/fluidcast-bench" "${args[@]}" | tee -a "$WORK/render.log" |
        table_rows >>"$WORK/render.md"
}

stream_step() {
    local args=(--gpu "$GPU" --particles 1m --size "$SIZE" --format jpeg --requests 0 --stream-seconds "$STREAM_SECONDS")
    echo "fluidcast-e2e-bench ${args[*]}" >>"$WORK/commands"
    log "fluidcast-e2e-bench ${args[*]}"
    timeout "$STEP_TIMEOUT" "$BUILD_DIR/bin/fluidcast-e2e-bench" "${args[@]}" | tee "$WORK/stream.log" |
        table_rows >"$WORK/stream.md"
}

# One line of the verdict table: what, measured value, the comparison, the target.
verdict() {
    local what=$1 measured=$2 op=$3 target=$4 met
    met=$(awk -v m="$measured" -v t="$target" -v op="$op" \
        'BEGIN { if (m == "") print "not measured"; else if (op == "<=" ? m + 0 <= t + 0 : m + 0 >= t + 0) print "yes"; else print "no" }')
    echo "| $what | ${measured:-–} | $op $target | $met |"
}

# Column $2 (awk field) of the row of $1 particles in the render table.
render_column() { awk -F'|' -v n="$1" -v f="$2" '$2 + 0 == n { v = $f; gsub(/ /, "", v); print v }' "$WORK/render.md"; }

report() {
    local million=$(particle_count 1m) sixteen=$(particle_count 16m) viewer_fps
    viewer_fps=$(awk -F'|' '{ v = $10; gsub(/ /, "", v); print v }' "$WORK/stream.md")
    echo "## Targets (bench/run_targets.sh)"
    echo
    machine_line
    echo "- renderer: $(head -n1 "$WORK/render.log")"
    echo "- date: $LOAD_DATE; git: $(git_revision)"
    echo "- load average (1/5/15 min): start $LOAD_START; end $(load_average)"
    echo "- command: GPU=$GPU FRAMES=$FRAMES LARGE_FRAMES=$LARGE_FRAMES STREAM_SECONDS=$STREAM_SECONDS bench/run_targets.sh"
    echo
    echo "| target | measured | target | met |"
    echo "|---|---|---|---|"
    verdict "1M particles, $SIZE, curvature 40 at 1/2, GPU ms" "$(render_column "$million" 14)" "<=" 2
    verdict "16M particles, same, GPU ms" "$(render_column "$sixteen" 14)" "<=" 20
    verdict "streaming 1M-particle frames, $SIZE JPEG, viewer fps" "$viewer_fps" ">=" 120
    echo
    sed 's/^/    /' "$WORK/commands"
    echo
    echo "| particles | size | smoothing | iter | scale | upload | depth | thickness | smoothing | composite | readback | encode | GPU sum | wall/frame | fps | GPU MiB |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
    cat "$WORK/render.md"
    echo
    echo "| particles | size | format | pushed | push fps | received | skipped | in flight | viewer fps | median ms | p99 ms |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|"
    cat "$WORK/stream.md"
}

main() {
    build_targets fluidcast-bench fluidcast-e2e-bench fluidcastd
    LOAD_START=$(load_average)
    LOAD_DATE=$(date -u '+%Y-%m-%d %H:%M UTC')
    render_step 1m "$FRAMES" || log "the 1M-particle run failed"
    render_step 16m "$LARGE_FRAMES" || log "the 16M-particle run failed"
    stream_step || log "the streaming run failed"
    report
    log "done"
}

main
