#!/usr/bin/env bash
# run_scaling.sh — how fluidcast's frame time and GPU memory grow along each axis of the
# pipeline: particles, image size, smoothing method, smoothing iterations, smoothing
# resolution scale.
#
#   bench/run_scaling.sh > scaling-report.md
#
# Builds fluidcast-bench (in $BUILD_DIR, default build-bench) and runs five sweeps, each
# varying one axis with the others at the reference configuration (64k particles,
# 1280x720, narrow-range filter at its default iterations, full-resolution smoothing):
#   1. particles 16k, 64k, 256k, 1m, 4m, 16m;
#   2. sizes 1280x720, 1920x1080, 2560x1440, 3840x2160;
#   3. each smoothing method (none, narrow, bilateral, binomial, curvature), default iterations;
#   4. iterations: curvature flow 10, 20, 40, 80; narrow-range 1, 2, 3, 5;
#   5. smoothing resolution scale 1, 0.5, 0.25 for curvature flow (40 iterations) and narrow.
# It prints a markdown report: machine, GL renderer, date, git revision, load average
# before and after, and for each sweep the exact command and fluidcast-bench's table
# (median per frame after one warm-up frame; per-stage GPU timer queries, wall ms, fps,
# GPU MiB the pipeline holds).
#
# The particle sweep stops early, and says so in the report, at the first count that
# would not fit in memory (MEM_PER_PARTICLE bytes each against MemAvailable) or whose step
# ran past STEP_TIMEOUT. Counts from LARGE_PARTICLES on are timed over LARGE_FRAMES frames
# (on llvmpipe 16M particles take many seconds per frame).
#
# Environment: BUILD_DIR; GPU (fluidcast-bench --gpu, default auto: the EGL device if there
# is one, else llvmpipe); FRAMES (timed frames per configuration, default 3); LARGE_FRAMES
# (default 1) and LARGE_PARTICLES (default 4m); PARTICLES (the particle sweep, default
# 16k,64k,256k,1m,4m,16m); SIZES (the size sweep, default 1280x720,1920x1080,2560x1440,
# 3840x2160); STEP_TIMEOUT (seconds one fluidcast-bench run may take, default 600);
# MEM_PER_PARTICLE (bytes, default 100: on llvmpipe, where the "GPU" buffers are host memory,
# fluidcast-bench peaked at 2.3 GB resident for 32M particles at 1280x720, 69 bytes each).
# 16m is the daemon's default max_particles (proto/PROTOCOL.md); the benchmark renders more:
# PARTICLES=...,32m goes on as far as memory allows.
# With the defaults it took 4 minutes on 2 cores with llvmpipe at load average 4-5.
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD_DIR=${BUILD_DIR:-$ROOT/build-bench}
GPU=${GPU:-auto}
FRAMES=${FRAMES:-3}
LARGE_FRAMES=${LARGE_FRAMES:-1}
LARGE_PARTICLES=${LARGE_PARTICLES:-4m}
PARTICLES=${PARTICLES:-16k,64k,256k,1m,4m,16m}
SIZES=${SIZES:-1280x720,1920x1080,2560x1440,3840x2160}
STEP_TIMEOUT=${STEP_TIMEOUT:-600}
MEM_PER_PARTICLE=${MEM_PER_PARTICLE:-100}
# The reference configuration every sweep holds fixed except its own axis.
REF_PARTICLES=64k
REF_SIZE=1280x720
REF_SMOOTHING=narrow
REF_ITERATIONS=default
REF_SCALE=1

BENCH=$BUILD_DIR/bin/fluidcast-bench
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

log() { echo "run_scaling: $*" >&2; }
. "$ROOT/bench/bench_lib.sh"

available_bytes() { awk '/^MemAvailable/ { printf "%.0f\n", $2 * 1024 }' /proc/meminfo; }

# Why a run of sweep $1 stopped early, one line per run in $WORK/<sweep>.stopped.
stop_sweep() { echo "$2" >>"$WORK/$1.stopped"; log "$1: $2"; }

# One fluidcast-bench run of sweep $1: its command into $WORK/<sweep>.commands, its table
# rows into <sweep>.md, its first line (the GL renderer) into renderer. Fails when the run
# fails or times out, with the reason in $WORK/step.err.
bench_step() {
    local sweep=$1 status=0
    shift
    local args=(--gpu "$GPU" --encode none "$@")
    echo "fluidcast-bench ${args[*]}" >>"$WORK/$sweep.commands"
    log "$sweep: fluidcast-bench ${args[*]}"
    timeout "$STEP_TIMEOUT" "$BENCH" "${args[@]}" >"$WORK/step.log" 2>"$WORK/step.err" || status=$?
    cat "$WORK/step.err" >&2
    [ -f "$WORK/renderer" ] || head -n1 "$WORK/step.log" >"$WORK/renderer"
    grep '^| [0-9]' "$WORK/step.log" >>"$WORK/$sweep.md" || true
    return "$status"
}

# Why the last bench_step failed, from its exit status $1: the time limit, or its last error line.
step_failure() {
    if [ "$1" = 124 ]; then echo "ran past STEP_TIMEOUT=${STEP_TIMEOUT}s"; else tail -n1 "$WORK/step.err"; fi
}

sweep_particles() {
    local particles count frames large
    large=$(particle_count "$LARGE_PARTICLES")
    for particles in ${PARTICLES//,/ }; do
        count=$(particle_count "$particles")
        if [ $((count * MEM_PER_PARTICLE)) -gt "$(available_bytes)" ]; then
            stop_sweep particles "stopped before $particles: $MEM_PER_PARTICLE bytes per particle exceed MemAvailable"
            return
        fi
        frames=$FRAMES
        [ "$count" -ge "$large" ] && frames=$LARGE_FRAMES
        bench_step particles --particles "$particles" --size "$REF_SIZE" --smoothing "$REF_SMOOTHING" \
            --iterations "$REF_ITERATIONS" --scale "$REF_SCALE" --frames "$frames" ||
            { stop_sweep particles "stopped at $particles: $(step_failure $?)"; return; }
    done
}

# A sweep that is one fluidcast-bench run of lists; a timeout ends only that sweep.
sweep_lists() {
    local sweep=$1
    shift
    bench_step "$sweep" --frames "$FRAMES" "$@" ||
        stop_sweep "$sweep" "incomplete: $(step_failure $?)"
}

run_sweeps() {
    local reference=(--particles "$REF_PARTICLES" --size "$REF_SIZE")
    sweep_particles
    sweep_lists sizes --particles "$REF_PARTICLES" --size "$SIZES" --smoothing "$REF_SMOOTHING" \
        --iterations "$REF_ITERATIONS" --scale "$REF_SCALE"
    sweep_lists methods "${reference[@]}" --smoothing none,narrow,bilateral,binomial,curvature \
        --iterations default --scale "$REF_SCALE"
    sweep_lists iterations "${reference[@]}" --smoothing curvature --iterations 10,20,40,80 --scale "$REF_SCALE"
    sweep_lists iterations "${reference[@]}" --smoothing narrow --iterations 1,2,3,5 --scale "$REF_SCALE"
    sweep_lists scale "${reference[@]}" --smoothing curvature --iterations 40 --scale 1,0.5,0.25
    sweep_lists scale "${reference[@]}" --smoothing narrow --iterations "$REF_ITERATIONS" --scale 1,0.5,0.25
}

print_sweep() {
    local sweep=$1 title=$2
    echo "### $title"
    echo
    sed 's/^/    /' "$WORK/$sweep.commands"
    echo
    if [ -f "$WORK/$sweep.stopped" ]; then
        sed 's/^/Note: /; s/$/./' "$WORK/$sweep.stopped"
        echo
    fi
    echo "| particles | size | smoothing | iter | scale | upload | depth | thickness | smoothing | composite | readback | encode | GPU sum | wall/frame | fps | GPU MiB |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
    cat "$WORK/$sweep.md" 2>/dev/null || true
    echo
}

machine() {
    machine_line
    echo "- fluidcast: $(cat "$WORK/renderer")"
    echo "- date: $LOAD_DATE; git: $(git_revision)"
    echo "- load average (1/5/15 min): before the build $LOAD_BEFORE_BUILD; start $LOAD_START;" \
         "end $(load_average) (the benchmark itself keeps the cores busy)"
    echo "- command: GPU=$GPU FRAMES=$FRAMES LARGE_FRAMES=$LARGE_FRAMES LARGE_PARTICLES=$LARGE_PARTICLES" \
         "PARTICLES=$PARTICLES SIZES=$SIZES STEP_TIMEOUT=$STEP_TIMEOUT MEM_PER_PARTICLE=$MEM_PER_PARTICLE" \
         "bench/run_scaling.sh"
    echo "- reference: $REF_PARTICLES particles, $REF_SIZE, $REF_SMOOTHING at $REF_ITERATIONS iterations," \
         "scale $REF_SCALE; median of $FRAMES frames after one warm-up frame ($LARGE_FRAMES from" \
         "$LARGE_PARTICLES particles on)"
}

main() {
    LOAD_BEFORE_BUILD=$(load_average)
    build_targets fluidcast-bench
    LOAD_START=$(load_average)
    LOAD_DATE=$(date -u '+%Y-%m-%d %H:%M UTC')
    log "load average $LOAD_START"
    run_sweeps
    echo "## Scaling"
    echo
    machine
    echo
    print_sweep particles "1. Particles"
    print_sweep sizes "2. Image size"
    print_sweep methods "3. Smoothing method (default iterations)"
    print_sweep iterations "4. Smoothing iterations"
    print_sweep scale "5. Smoothing resolution scale"
    log "done"
}

main
