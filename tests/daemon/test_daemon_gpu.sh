#!/usr/bin/env bash
# tests/daemon: GPU selection as an operator sees it (fluidcastd --gpu).
#   1. --gpu cuda:0: on a machine whose EGL has no NVIDIA device (this one),
#      exit 1 with a message naming cuda:0, EGL_NV_device_cuda and a likely
#      cause; where the NVIDIA EGL driver is present, it starts on CUDA 0 and
#      says so;
#   2. --gpu auto: without a GPU it logs, as a warning, that it falls back to
#      llvmpipe and the likely cause; with one it logs the device it chose.
#      Either way it logs "GPU: <device>", and `fluidcast info` prints the
#      renderer and that device;
#   3. bad values (cuda:, cuda:x, cuda:-1, gpu0) are usage errors: exit 2.
# usage: test_daemon_gpu.sh FLUIDCASTD FLUIDCAST WORK
set -euo pipefail
[ $# -eq 3 ] || { echo "usage: $0 FLUIDCASTD FLUIDCAST WORK" >&2; exit 2; }
DAEMON=$1 CLI=$2 WORK=$3
fail() { echo "FAIL: $*" >&2; exit 1; }
DAEMON_PID=""
stop_daemon() {
    if [ -n "$DAEMON_PID" ]; then
        kill "$DAEMON_PID" 2> /dev/null || true
        wait "$DAEMON_PID" 2> /dev/null || true
        DAEMON_PID=""
    fi
}
trap stop_daemon EXIT
rm -rf "$WORK"
mkdir -p "$WORK"

echo "== bad --gpu values"
for bad in cuda: cuda:x cuda:-1 gpu0 "cuda:0 "; do
    status=0
    "$DAEMON" --gpu "$bad" --listen 127.0.0.1:0 > "$WORK/bad.log" 2>&1 || status=$?
    [ "$status" -eq 2 ] || fail "--gpu '$bad': exit $status, expected 2"
    grep -q "cuda:N" "$WORK/bad.log" || fail "--gpu '$bad': the message does not list cuda:N: $(cat "$WORK/bad.log")"
done

# Starts the daemon with args; waits for the port file. 1 when it exits first.
start() {
    rm -f "$WORK/port"
    "$DAEMON" --listen 127.0.0.1:0 --port-file "$WORK/port" "$@" > "$WORK/daemon.log" 2>&1 &
    DAEMON_PID=$!
    for _ in $(seq 600); do
        [ -s "$WORK/port" ] && return 0
        if ! kill -0 "$DAEMON_PID" 2> /dev/null; then
            wait "$DAEMON_PID" || EXIT_STATUS=$?
            DAEMON_PID=""
            return 1
        fi
        sleep 0.1
    done
    fail "no port file within 60 s: $(cat "$WORK/daemon.log")"
}

echo "== --gpu cuda:0"
EXIT_STATUS=0
if start --gpu cuda:0; then
    grep -q "info  GPU: EGL device [0-9]*.*CUDA 0" "$WORK/daemon.log" ||
        fail "--gpu cuda:0 started but does not log CUDA 0: $(cat "$WORK/daemon.log")"
    echo "this machine has CUDA device 0 through EGL: $(grep 'GPU:' "$WORK/daemon.log")"
    stop_daemon
else
    [ "$EXIT_STATUS" -eq 1 ] || fail "--gpu cuda:0: exit $EXIT_STATUS, expected 1"
    grep -q -- "--gpu cuda:0: none of the [0-9]* EGL device(s) reports a CUDA device number (EGL_NV_device_cuda): no NVIDIA EGL driver" \
        "$WORK/daemon.log" || fail "--gpu cuda:0 does not say why: $(cat "$WORK/daemon.log")"
    grep -q "Likely cause: ." "$WORK/daemon.log" || fail "--gpu cuda:0 names no likely cause"
    cat "$WORK/daemon.log"
fi

echo "== --gpu auto"
start --gpu auto || fail "--gpu auto did not start: $(cat "$WORK/daemon.log")"
cat "$WORK/daemon.log"
if grep -q "rendering with Mesa's llvmpipe" "$WORK/daemon.log"; then
    grep -q "warn  --gpu auto: no GPU EGL device.*: rendering with Mesa's llvmpipe .*Likely cause: [a-zA-Z/]" \
        "$WORK/daemon.log" || fail "the fallback is not a warning with a likely cause"
    device="Mesa surfaceless platform (no device)"
else
    device=$(sed -n 's/.*info  GPU: \(EGL device .*\)$/\1/p' "$WORK/daemon.log")
    [ -n "$device" ] || fail "--gpu auto chose a GPU without logging which"
fi
grep -q "info  GPU: $device\$" "$WORK/daemon.log" || fail "no 'GPU: $device' line"
out=$("$CLI" info --server "127.0.0.1:$(cat "$WORK/port")") || fail "fluidcast info failed"
echo "$out"
grep -q "^renderer:     ." <<< "$out" || fail "fluidcast info prints no renderer"
grep -qF "device:       $device" <<< "$out" || fail "fluidcast info does not print the device '$device'"
grep -q "^capabilities:.* device" <<< "$out" || fail "fluidcast info: DEVICE not granted"
stop_daemon
echo OK
