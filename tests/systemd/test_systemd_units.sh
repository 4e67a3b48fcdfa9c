#!/usr/bin/env bash
# tests/systemd: the unit files of deploy/systemd as systemd sees them.
#   1. `systemd-analyze verify` on fluidcastd.socket, fluidcastd.service, the
#      template fluidcastd@.service and its instance fluidcastd@0.service
#      passes without one line of output (a warning fails the test), with
#      /usr/bin/fluidcastd replaced by the built binary (verify requires
#      ExecStart's program to exist); a unit with a misspelt key does print
#      a warning (the check can fail);
#   2. each service's ExecStart runs for real, systemd's variables replaced
#      the way systemd fills them (instance "software", the credentials and
#      runtime folders), and `fluidcast info` gets an answer with the token.
# Exit 77 (skipped) without systemd-analyze.
#
# usage: test_systemd_units.sh UNIT_DIR FLUIDCASTD FLUIDCAST WORK
set -euo pipefail
[ $# -eq 4 ] || { echo "usage: $0 UNIT_DIR FLUIDCASTD FLUIDCAST WORK" >&2; exit 2; }
UNITS=$1 DAEMON=$2 CLI=$3 WORK=$4
fail() { echo "FAIL: $*" >&2; exit 1; }
command -v systemd-analyze > /dev/null || { echo "SKIP: systemd-analyze not installed (apt-get install systemd)"; exit 77; }

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
mkdir -p "$WORK/units" "$WORK/cred" "$WORK/run"

echo "== units with ExecStart=$DAEMON"
for f in fluidcastd.socket fluidcastd.service fluidcastd@.service; do
    [ -f "$UNITS/$f" ] || fail "missing $UNITS/$f"
    sed "s#/usr/bin/fluidcastd#$DAEMON#g" "$UNITS/$f" > "$WORK/units/$f"
done
grep -q "^ExecStart=$DAEMON " "$WORK/units/fluidcastd.service" || fail "fluidcastd.service does not run /usr/bin/fluidcastd"
grep -q "^ExecStart=$DAEMON " "$WORK/units/fluidcastd@.service" || fail "fluidcastd@.service does not run /usr/bin/fluidcastd"
# An instance: verify refuses a template alone for some checks, and a path
# with ':' (as in cuda:0) is not read as a unit file path.
cp "$WORK/units/fluidcastd@.service" "$WORK/units/fluidcastd@0.service"

verify() {
    local out
    out=$(cd "$WORK/units" && systemd-analyze verify --man=no "$@" 2>&1) || { echo "$out"; return 1; }
    [ -z "$out" ] || { echo "$out"; return 1; }
}
for unit in fluidcastd.socket fluidcastd.service fluidcastd@.service fluidcastd@0.service; do
    echo "== systemd-analyze verify $unit"
    verify "./$unit" || fail "systemd-analyze verify $unit is not silent"
done
echo "== a misspelt key is reported"
sed 's/^ProtectClock=/ProtectClok=/' "$WORK/units/fluidcastd.service" > "$WORK/units/misspelt.service"
if verify ./misspelt.service > "$WORK/misspelt.log"; then fail "systemd-analyze verify missed a misspelt key"; fi
grep -q "Unknown key 'ProtectClok'" "$WORK/misspelt.log" || fail "unexpected verify output: $(cat "$WORK/misspelt.log")"
rm "$WORK/units/misspelt.service"
grep -q '^MemoryDenyWriteExecute' "$WORK/units/fluidcastd.service" &&
    fail "MemoryDenyWriteExecute breaks llvmpipe's JIT: it must stay off"

# ExecStart of a unit with the variables systemd would fill in.
exec_start() {
    local unit=$1 line
    line=$(sed -n 's/^ExecStart=//p' "$WORK/units/$unit")
    line=${line//%I/software}
    line=${line//%i/software}
    line=${line//'${CREDENTIALS_DIRECTORY}'/$WORK/cred}
    line=${line//'${RUNTIME_DIRECTORY}'/$WORK/run}
    line=${line//'$FLUIDCASTD_OPTIONS'/}
    printf '%s' "$line"
}
TOKEN=$(head -c 24 /dev/urandom | od -An -tx1 | tr -d ' \n')
printf '%s\n' "$TOKEN" > "$WORK/cred/token"
chmod 600 "$WORK/cred/token"

# Runs the unit's ExecStart plus extra arguments; waits for the port file.
run_unit() {
    local unit=$1; shift
    local -a cmd
    read -r -a cmd <<< "$(exec_start "$unit")"
    rm -f "$WORK/port"
    echo "== $unit: ${cmd[*]} $*"
    "${cmd[@]}" "$@" --port-file "$WORK/port" > "$WORK/$unit.log" 2>&1 &
    DAEMON_PID=$!
    for _ in $(seq 600); do
        [ -s "$WORK/port" ] && return 0
        kill -0 "$DAEMON_PID" 2> /dev/null || { cat "$WORK/$unit.log"; fail "$unit: the daemon exited"; }
        sleep 0.1
    done
    fail "$unit: no port file within 60 s"
}

run_unit fluidcastd.service --listen 127.0.0.1:0 --metrics-listen 127.0.0.1:0
out=$("$CLI" info --server "127.0.0.1:$(cat "$WORK/port")" --token-file "$WORK/cred/token") ||
    fail "fluidcastd.service's command line: fluidcast info failed"
grep -q '^renderer:' <<< "$out" || fail "fluidcast info: $out"
if "$CLI" info --server "127.0.0.1:$(cat "$WORK/port")" > /dev/null 2>&1; then
    fail "fluidcastd.service's command line serves without the token"
fi
stop_daemon

run_unit fluidcastd@.service
[ -S "$WORK/run/fluidcast.sock" ] || fail "fluidcastd@software did not listen on its runtime folder's socket"
out=$("$CLI" info --server "unix:$WORK/run/fluidcast.sock" --token-file "$WORK/cred/token") ||
    fail "fluidcastd@software: fluidcast info over the Unix socket failed"
grep -q '^renderer:.*llvmpipe' <<< "$out" || fail "fluidcastd@software: $out"
stop_daemon
echo "OK"
