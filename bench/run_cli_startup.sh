#!/usr/bin/env bash
# run_cli_startup.sh — the fluidcast command's own cost, compared between builds: `fluidcast --version`
# (process start alone) and a whole `fluidcast snapshot` of the drop scene to PNG against one fluidcastd
# already running (run_snapshot_vs_vtk.sh's command), each build's binary interleaved with the others
# for REPS rounds; medians of the wall time and of the command's own CPU time (user + sys of the
# client process: the server's time is not in it).
#
#   bench/run_cli_startup.sh before=/path/to/old/fluidcast after=build-bench/bin/fluidcast > startup.md
#
# Without arguments: BUILD_DIR's fluidcast alone. Environment: PARTICLES (default 64k), SIZE (default
# 1024x768), REPS (default 20), ESTIMATE=1 (leave --radius out: the command estimates it from the
# particles, as a user's snapshot does), BUILD_DIR (default build-bench: its fluidcastd and
# fluidcast-bench serve and make the scene), NO_BUILD=1.
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD_DIR=${BUILD_DIR:-$ROOT/build-bench}
PARTICLES=${PARTICLES:-64k}
SIZE=${SIZE:-1024x768}
REPS=${REPS:-20}
WORK=$(mktemp -d)
log() { echo "run_cli_startup: $*" >&2; }
. "$ROOT/bench/bench_lib.sh"
. "$ROOT/bench/snapshot_lib.sh"

[ $# -gt 0 ] || set -- "fluidcast=$BUILD_DIR/bin/fluidcast"
if [ "${NO_BUILD:-0}" = 1 ]; then
    build_targets fluidcastd fluidcast-bench   # checks that they are there
else
    build_targets fluidcastd fluidcast-bench fluidcast-cli
fi
for spec in "$@"; do
    [ -x "${spec#*=}" ] || { log "not an executable: ${spec#*=}"; exit 1; }
done

start_daemon software
RADIUS=$("$BUILD_DIR/bin/fluidcast-bench" --particles "$PARTICLES" --write-scene "$WORK/scene.f32" | awk '{ print $6 }')

LOAD_START=$(load_average)
DATE=$(date -u '+%Y-%m-%d %H:%M UTC')
RADIUS_ARGS=(--radius "$RADIUS")
[ "${ESTIMATE:-0}" = 1 ] && RADIUS_ARGS=()
SNAPSHOT_ARGS=(snapshot "$WORK/scene.f32" -o "$WORK/snap.png" --server "127.0.0.1:$(cat "$WORK/port")" --size "$SIZE"
               "${RADIUS_ARGS[@]}" "${CAMERA[@]}" "${SMOOTHING[@]}")
# Each (binary, command) pair once per round, rounds repeated; the child's own rusage from wait4.
TABLE=$(python3 - "$REPS" "$@" -- "${SNAPSHOT_ARGS[@]}" <<'EOF'
import os, statistics, sys, time
args = sys.argv[1:]
reps = int(args[0]); split = args.index('--')
binaries = [a.split('=', 1) for a in args[1:split]]
snapshot = args[split + 1:]
commands = [(f"{label} --version", [path, '--version']) for label, path in binaries]
commands += [(f"{label} snapshot", [path] + snapshot) for label, path in binaries]
wall = {c[0]: [] for c in commands}; cpu = {c[0]: [] for c in commands}
devnull = os.open(os.devnull, os.O_WRONLY)
for _ in range(reps):
    for name, argv in commands:
        t0 = time.perf_counter()
        pid = os.fork()
        if pid == 0:
            os.dup2(devnull, 1); os.dup2(devnull, 2)
            os.execv(argv[0], argv)
        _, status, ru = os.wait4(pid, 0)
        if status != 0:
            sys.exit(f"{name} failed (status {status})")
        wall[name].append((time.perf_counter() - t0) * 1000)
        cpu[name].append((ru.ru_utime + ru.ru_stime) * 1000)
first = {kind: statistics.median(wall[f"{binaries[0][0]} {kind}"]) for kind in ('--version', 'snapshot')}
print("| binary, command | runs | wall ms, median (min-max) | client CPU ms (user+sys), median | wall vs first binary |")
print("|---|---|---|---|---|")
for name, _ in commands:
    w = wall[name]; kind = name.rsplit(' ', 1)[1]
    print(f"| {name} | {len(w)} | {statistics.median(w):.1f} ({min(w):.1f}-{max(w):.1f}) | "
          f"{statistics.median(cpu[name]):.1f} | {statistics.median(w) / first[kind]:.3f} |")
EOF
)

echo "### fluidcast's start-up: --version and a whole snapshot ($PARTICLES particles, $SIZE, PNG)"
echo
machine_line
echo "- date: $DATE; git: $(git_revision); load average (1/5/15 min): start $LOAD_START; end $(load_average)"
echo "- daemon: $BUILD_DIR/bin/fluidcastd --gpu software (llvmpipe), running throughout; scene: fluidcast-bench --particles $PARTICLES --write-scene"
echo "- command: ${0#"$ROOT"/} $* (REPS=$REPS, ESTIMATE=${ESTIMATE:-0}, interleaved); snapshot as bench/run_snapshot_vs_vtk.sh: \`fluidcast ${SNAPSHOT_ARGS[*]/#$WORK\//}\`"
for spec in "$@"; do
    echo "- ${spec%%=*}: ${spec#*=}, $(ldd "${spec#*=}" | wc -l) shared libraries in ldd"
done
echo
echo "$TABLE"
