#!/usr/bin/env bash
# run_render_pipeline.sh — does fluidcastd wait for `fluidcast render` between frames?
# Runs two fluidcast binaries (e.g. before and after a change) alternately on one
# sequence against one fluidcastd started here with --log-level debug, and reads the
# daemon's log: for each frame after the first, the time from "IMAGE ... queued"
# (frame i rendered) to "FRAME" (frame i + 1 received and parsed) is time the daemon
# had nothing to render, waiting for the client (decoding the image, encoding the
# video, writing, reading the next file, uploading it).
#
#   bench/run_render_pipeline.sh CLI_A CLI_B 'frames/frame_%04d.ply' > report.md
#
# Environment: RUNS (runs of each, alternating A B A B ..., default 3); SIZE (default
# 1280x720); OUT (output extension: mp4, webm or png, default mp4); FLUIDCASTD (default
# build/bin/fluidcastd); GPU (--gpu, default auto). Prints a markdown report: machine,
# GL renderer, date, load average, the command, and per run the wall time the CLI
# reports and the daemon's idle time between frames; then the medians and their ratio B/A.
set -euo pipefail

if [[ $# -ne 3 ]]; then
    echo "usage: $0 CLI_A CLI_B FRAMES_PATTERN" >&2
    exit 2
fi
cli_a=$1 cli_b=$2 frames=$3
runs=${RUNS:-3} size=${SIZE:-1280x720} ext=${OUT:-mp4}
daemon_bin=${FLUIDCASTD:-build/bin/fluidcastd}
work=$(mktemp -d /tmp/fluidcast-pipeline-XXXXXX)
port=$((20000 + RANDOM % 40000))

"$daemon_bin" --listen 127.0.0.1:$port --gpu "${GPU:-auto}" --log-level debug >"$work/daemon.log" 2>&1 &
daemon_pid=$!
trap 'kill $daemon_pid 2>/dev/null; wait $daemon_pid 2>/dev/null; rm -rf "$work"' EXIT
for _ in $(seq 50); do
    grep -q "listening" "$work/daemon.log" 2>/dev/null && break
    sleep 0.2
done

# Milliseconds of idle between frames in the log lines after line $1: sum, frames.
idle_since() {
    tail -n +"$(($1 + 1))" "$work/daemon.log" | awk '
        function ms(stamp,  t) { split(substr(stamp, 12, 12), t, ":"); return (t[1] * 3600 + t[2] * 60 + t[3]) * 1000 }
        / IMAGE of .* queued/ { last = ms($1); frames++ }
        / FRAME of / { if (last) { idle += ms($1) - last; last = 0 } }
        END { printf "%.0f %d\n", idle, frames }'
}

run_one() {
    local cli=$1 out
    local before
    before=$(wc -l <"$work/daemon.log")
    if [[ $ext == png ]]; then out="$work/png/f_%04d.png"; rm -rf "$work/png"; else out="$work/out.$ext"; fi
    local line
    line=$("$cli" render "$frames" -o "$out" --server 127.0.0.1:$port --size "$size" | grep '^rendered')
    sleep 0.3   # the daemon's last lines
    local seconds=${line##* in }
    seconds=${seconds%% s *}
    read -r idle count < <(idle_since "$before")
    echo "$seconds $idle $count"
}

echo "## fluidcast render pipeline: $(date -u '+%Y-%m-%d %H:%M UTC')"
echo
echo "- machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2 / 1048576}' /proc/meminfo)"
echo "- renderer: $(grep -m1 -o 'GL_RENDERER: .*' "$work/daemon.log" || echo 'see fluidcastd log')"
echo "- load average at the start: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "- command: RUNS=$runs SIZE=$size OUT=$ext $0 $cli_a $cli_b '$frames'"
echo "- A: $cli_a; B: $cli_b"
echo
echo "| run | binary | wall s | daemon idle between frames, ms (sum) | frames | idle per frame, ms |"
echo "|---|---|---|---|---|---|"
declare -a wall_a wall_b idle_a idle_b
for r in $(seq "$runs"); do
    for which in A B; do
        cli=$cli_a
        [[ $which == B ]] && cli=$cli_b
        read -r seconds idle count < <(run_one "$cli")
        per=$(awk -v i="$idle" -v n="$count" 'BEGIN { printf "%.1f", (n > 1 ? i / (n - 1) : 0) }')
        echo "| $r | $which | $seconds | $idle | $count | $per |"
        if [[ $which == A ]]; then wall_a+=("$seconds"); idle_a+=("$per"); else wall_b+=("$seconds"); idle_b+=("$per"); fi
    done
done
median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
ma=$(median "${wall_a[@]}") mb=$(median "${wall_b[@]}")
ia=$(median "${idle_a[@]}") ib=$(median "${idle_b[@]}")
echo
echo "Medians: wall A $ma s, B $mb s (B/A $(awk -v a="$ma" -v b="$mb" 'BEGIN { printf "%.2f", b / a }')); daemon idle per frame A $ia ms, B $ib ms."
echo "Load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
