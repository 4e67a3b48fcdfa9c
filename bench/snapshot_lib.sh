# snapshot_lib.sh — what the snapshot benchmarks share (run_snapshot_vs_vtk.sh,
# run_cli_startup.sh): the drop scene's view and smoothing, and a fluidcastd to
# snapshot against. Sourced after bench_lib.sh, by scripts that set ROOT,
# BUILD_DIR and WORK and define log(); it stops the daemon and removes WORK on exit.

# The drop scene's camera (bench/scene.c, as bench/peer/vtk_fluid_bench.py), and
# VTK 9.1's fixed narrow-range filter: 3 passes, a 5-pixel radius.
# shellcheck disable=SC2034,SC2054  # used by the sourcing script; the commas are inside values
CAMERA=(--eye 2,-2.9,1.9 --target 0,0,0.25 --up z --fov 40)
# shellcheck disable=SC2034
SMOOTHING=(--smoothing narrow --iterations 3 --filter-radius 5)

DAEMON_PID=""
cleanup() {
    [ -n "$DAEMON_PID" ] && kill "$DAEMON_PID" 2>/dev/null && wait "$DAEMON_PID" 2>/dev/null
    rm -rf "$WORK"
}
trap cleanup EXIT

# fluidcastd from $BUILD_DIR on a free loopback port, on GL device $1 (auto,
# software, N); its port in $WORK/port, its PID in DAEMON_PID.
start_daemon() {
    "$BUILD_DIR/bin/fluidcastd" --gpu "$1" --listen 127.0.0.1:0 --port-file "$WORK/port" >"$WORK/daemon.log" 2>&1 &
    DAEMON_PID=$!
    for _ in $(seq 100); do [ -s "$WORK/port" ] && return 0; sleep 0.1; done
    log "fluidcastd did not start: $(cat "$WORK/daemon.log")"; exit 1
}
