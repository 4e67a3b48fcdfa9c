#!/bin/sh
# `fluidcast spacemouse --dump` ends on SIGINT (exit 0) while a scripted
# Compact streams its held report under umockdev-run, i.e. with the interrupt
# transfer in flight. Exits 77 (skip) only when umockdev-run is not installed.
#   dump_sigint.sh FLUIDCAST DIR
set -u
fluidcast=$1 dir=$2
if ! command -v umockdev-run >/dev/null 2>&1; then
    echo "umockdev-run not found (apt-get install umockdev): skipped"
    exit 77
fi
ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0"
export ASAN_OPTIONS
out=$(mktemp)
trap 'rm -f "$out"' EXIT
umockdev-run --device "$dir/compact.umockdev" --ioctl /dev/bus/usb/001/005="$dir/compact_hold.ioctl" \
    -- "$fluidcast" spacemouse --dump >"$out" 2>/dev/null &
runner=$!
# wait for reports to flow, then interrupt the fluidcast process itself
child=""
# (waits, not timings: generous for a loaded machine under AddressSanitizer)
for _ in $(seq 300); do
    child=$(pgrep -P "$runner" -x fluidcast | head -n 1)
    [ -n "$child" ] && grep -q '^report 1:' "$out" && break
    sleep 0.1
done
if [ -z "$child" ] || ! grep -q '^report 1:' "$out"; then
    echo "no reports within 30 s" >&2
    kill "$runner" 2>/dev/null
    exit 1
fi
kill -INT "$child"
for _ in $(seq 300); do
    kill -0 "$runner" 2>/dev/null || break
    sleep 0.1
done
if kill -0 "$runner" 2>/dev/null; then
    echo "still running 30 s after SIGINT" >&2
    kill -KILL "$child" 2>/dev/null
    exit 1
fi
wait "$runner"
status=$?
echo "$(grep -c '^report' "$out") reports, then SIGINT: exit status $status"
[ $status -eq 0 ]
