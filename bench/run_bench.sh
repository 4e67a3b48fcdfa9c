#!/usr/bin/env bash
# run_bench.sh — fluidcast against its peer, VTK's vtkOpenGLFluidMapper (narrow-range
# filter), on the same particles, camera, image sizes and machine, in one run.
#
#   bench/run_bench.sh > bench-report.md
#
# Builds fluidcast-bench (in $BUILD_DIR, default build-bench), exports each particle
# count's drop scene as .f32 so both renderers read identical data, times both, and
# prints a markdown report: machine, GL renderers, load, the raw tables and the ratio
# fluidcast fps / VTK fps per configuration. fluidcast runs without smoothing, with
# curvature flow (40 iterations) and with its narrow-range filter at VTK's 3 passes and filter radius.
# Then the paper's configurations (van der Laan et al. 2009, Table 1: 64K particles,
# 1024x768): curvature flow at 1/4 resolution 15 iterations, 1/2 resolution 40, full
# resolution 100, and the bilateral filter (fluidcast's default passes), next to VTK.
# It also leaves one picture of each renderer in $IMAGE_DIR (default bench/peer/:
# fluidcast.png, vtk.png), of the last particle count at the last size.
#
# Without $DISPLAY, VTK (Debian's python3-vtk9, an X build) runs under `xvfb-run -a` with
# Mesa llvmpipe, and fluidcast is told --gpu software so both rasterize on the same CPU
# cores. With $DISPLAY set, VTK uses that display and fluidcast --gpu auto: check that the
# two GL renderer lines of the report name the same device.
#
# Environment: FRAMES (timed frames per configuration, default 3), PARTICLES (default
# 16k,64k), SIZES (default 640x360,1280x720), PAPER=0 skips the paper's configurations,
# IMAGE_DIR (where the pictures go; set it elsewhere for trial runs at other sizes),
# STEP_TIMEOUT (seconds any one step may take, default 600). With the defaults it takes
# about one minute on 2 cores with llvmpipe when the machine is otherwise idle.
# Needs: python3-vtk9 python3-numpy xvfb xauth (Debian packages), installed first by
# `deploy/setup.sh --bench` with everything the build needs.
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
"$ROOT/deploy/setup.sh" --bench
BUILD_DIR=${BUILD_DIR:-$ROOT/build-bench}
FRAMES=${FRAMES:-3}
PARTICLES=${PARTICLES:-16k,64k}
SIZES=${SIZES:-640x360,1280x720}
PAPER=${PAPER:-1}
STEP_TIMEOUT=${STEP_TIMEOUT:-600}
PEER_DIR=$ROOT/bench/peer
IMAGE_DIR=${IMAGE_DIR:-$PEER_DIR}
VTK_PYTHON=/usr/bin/python3   # Debian's: python3-vtk9 is not in other interpreters
VTK_ITERATIONS=3              # VTK 9.1's narrow-range default; Python cannot change it
VTK_FILTER_RADIUS=5           # likewise its filter radius in pixels
PEER_ITERATIONS=40            # curvature flow in the peer comparison
PAPER_PARTICLES=64k
PAPER_SIZE=1024x768
# Table 1's curvature-flow rows: smoothing resolution and iterations
PAPER_CURVATURE=("0.25 15" "0.5 40" "1 100")

BENCH=$BUILD_DIR/bin/fluidcast-bench
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

log() { echo "run_bench: $*" >&2; }
. "$ROOT/bench/bench_lib.sh"

check_peer() {
    "$VTK_PYTHON" -c 'import numpy, vtkmodules.vtkRenderingOpenGL2' 2>/dev/null ||
        { log "VTK or numpy missing: apt-get install python3-vtk9 python3-numpy"; exit 1; }
    if [ -z "${DISPLAY:-}" ] && ! command -v xvfb-run >/dev/null; then
        log "no \$DISPLAY and no xvfb-run: apt-get install xvfb xauth"; exit 1
    fi
}

# fluidcast and VTK on the same GL implementation (see the header).
if [ -n "${DISPLAY:-}" ]; then
    GPU=auto
    run_vtk() { timeout "$STEP_TIMEOUT" "$VTK_PYTHON" "$PEER_DIR/vtk_fluid_bench.py" "$@"; }
else
    GPU=software
    run_vtk() {
        timeout "$STEP_TIMEOUT" xvfb-run -a env LIBGL_ALWAYS_SOFTWARE=1 \
            "$VTK_PYTHON" "$PEER_DIR/vtk_fluid_bench.py" "$@"
    }
fi

run_fluidcast() { timeout "$STEP_TIMEOUT" "$BENCH" --gpu "$GPU" --encode none --frames "$FRAMES" "$@"; }

table_rows() { grep '^| [0-9]' || true; }

# Exports the scene of one particle count once; prints the radius fluidcast renders it with.
export_scene() {
    local path=$WORK/scene_$1.f32
    [ -f "$path.radius" ] || "$BENCH" --particles "$1" --write-scene "$path" | awk '{ print $6 }' >"$path.radius"
    cat "$path.radius"
}

# One fluidcast-bench run: rows appended to $out/fluidcast.md, the whole output to fluidcast.log.
bench_fluidcast() {
    local out=$1
    shift
    run_fluidcast "$@" | tee -a "$out/fluidcast.log" | table_rows >>"$out/fluidcast.md"
}

# The peer configurations of one particle count; the optional image gets
# curvature flow at the last size.
bench_fluidcast_peer() {
    local out=$1 particles=$2 sizes=$3 image=${4:-}
    local args=(--particles "$particles" --size "$sizes")
    bench_fluidcast "$out" "${args[@]}" --smoothing narrow --iterations "$VTK_ITERATIONS" \
        --filter-radius "$VTK_FILTER_RADIUS"
    [ -n "$image" ] && args+=(--image "$image")
    bench_fluidcast "$out" "${args[@]}" --smoothing none,curvature --iterations "$PEER_ITERATIONS"
}

bench_fluidcast_paper() {
    local out=$1 args=(--particles "$PAPER_PARTICLES" --size "$PAPER_SIZE") config scale iterations
    for config in "${PAPER_CURVATURE[@]}"; do
        read -r scale iterations <<<"$config"
        bench_fluidcast "$out" "${args[@]}" --smoothing curvature --scale "$scale" --iterations "$iterations"
    done
    bench_fluidcast "$out" "${args[@]}" --smoothing bilateral --iterations default
    bench_fluidcast "$out" "${args[@]}" --smoothing narrow --iterations "$VTK_ITERATIONS" \
        --filter-radius "$VTK_FILTER_RADIUS"
}

# VTK at every size for one particle count: rows appended to $out/vtk.md; the
# optional image gets the frame at size $image_size.
bench_vtk() {
    local out=$1 particles=$2 sizes=$3 image_size=${4:-} radius size
    radius=$(export_scene "$particles")
    for size in ${sizes//,/ }; do
        local args=(--scene "$WORK/scene_$particles.f32" --radius "$radius" --size "$size" --frames "$FRAMES")
        [ "$size" = "$image_size" ] && args+=(--image "$IMAGE_DIR/vtk.png")
        run_vtk "${args[@]}" | tee -a "$out/vtk.log" | table_rows >>"$out/vtk.md"
    done
}

# Joins fluidcast rows with the VTK row of the same particles and size.
ratio_table() {
    echo "| particles | size | fluidcast smoothing | iter | scale | fluidcast ms | fluidcast fps | VTK ms (narrow-range, $VTK_ITERATIONS iter, radius $VTK_FILTER_RADIUS) | VTK fps | fluidcast fps / VTK fps |"
    echo "|---|---|---|---|---|---|---|---|---|---|"
    awk -F'|' '
        function trim(s) { gsub(/^ +| +$/, "", s); return s }
        FNR == NR { key = trim($2) " " trim($3); vtk_ms[key] = trim($7); vtk_fps[key] = trim($8); next }
        {
            key = trim($2) " " trim($3)
            if (!(key in vtk_fps)) next
            ms = trim($15); fps = trim($16)   # wall/frame and fps, before the GPU memory column
            printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %.2f |\n", trim($2), trim($3), trim($4), trim($5),
                   trim($6), ms, fps, vtk_ms[key], vtk_fps[key], fps / vtk_fps[key]
        }' "$1" "$2"
}

print_tables() {
    local title=$1 dir=$2
    echo "### $title: fluidcast-bench (median per frame; stage columns are GPU timer queries)"
    echo
    echo "| particles | size | smoothing | iter | scale | upload | depth | thickness | smoothing | composite | readback | encode | GPU sum | wall/frame | fps | GPU MiB |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
    cat "$dir/fluidcast.md"
    echo
    echo "### $title: VTK vtkOpenGLFluidMapper (median wall ms per Render() + RGBA8 readback)"
    echo
    echo "| particles | size | filter | iter | first frame ms | wall/frame | fps |"
    echo "|---|---|---|---|---|---|---|"
    cat "$dir/vtk.md"
    echo
    echo "### $title: ratio"
    echo
    ratio_table "$dir/vtk.md" "$dir/fluidcast.md"
    echo
}

machine() {
    local logs=$1
    machine_line
    echo "- fluidcast: $(head -n1 "$logs/fluidcast.log")"
    echo "- VTK $("$VTK_PYTHON" -c 'import vtkmodules; print(vtkmodules.__version__)'): $(head -n1 "$logs/vtk.log")"
    echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC'); git: $(git_revision)"
    echo "- load average (1/5/15 min): before the build $LOAD_BEFORE_BUILD; start $LOAD_START;" \
         "end $(load_average) (the benchmark itself keeps 2 cores busy)"
    echo "- command: FRAMES=$FRAMES PARTICLES=$PARTICLES SIZES=$SIZES PAPER=$PAPER bench/run_bench.sh" \
         "(fluidcast --gpu $GPU; VTK on ${DISPLAY:-xvfb-run + LIBGL_ALWAYS_SOFTWARE=1})"
}

main() {
    check_peer
    LOAD_BEFORE_BUILD=$(load_average)
    build_targets fluidcast-bench
    LOAD_START=$(load_average)
    log "load average $LOAD_START"
    local peer=$WORK/peer paper=$WORK/paper last_particles=${PARTICLES##*,} last_size=${SIZES##*,}
    mkdir -p "$peer" "$paper"
    for particles in ${PARTICLES//,/ }; do
        log "peer configurations, $particles particles"
        if [ "$particles" = "$last_particles" ]; then
            bench_fluidcast_peer "$peer" "$particles" "$SIZES" "$IMAGE_DIR/fluidcast.png"
            bench_vtk "$peer" "$particles" "$SIZES" "$last_size"
        else
            bench_fluidcast_peer "$peer" "$particles" "$SIZES"
            bench_vtk "$peer" "$particles" "$SIZES"
        fi
    done
    if [ "$PAPER" = 1 ]; then
        log "paper configurations"
        bench_fluidcast_paper "$paper"
        bench_vtk "$paper" "$PAPER_PARTICLES" "$PAPER_SIZE"
    fi
    echo "## fluidcast vs VTK vtkOpenGLFluidMapper"
    echo
    machine "$peer"
    echo
    print_tables "Peer configurations" "$peer"
    if [ "$PAPER" = 1 ]; then
        print_tables "Paper configurations (Table 1: 64K particles, 1024x768)" "$paper"
        echo "Paper, GeForce 8800 GTS: curvature flow 1/4 res 15 iterations 17.5 ms, 1/2 res 40 iterations" \
             "19.6 ms, full res 100 iterations 50 ms; bilateral Gaussian 18.1 ms."
    fi
    log "done; pictures of the last peer configuration in $IMAGE_DIR (fluidcast.png, vtk.png)"
}

main
