#!/bin/sh
# Runs a program in a umockdev sandbox holding one scripted USB device at
# /dev/bus/usb/001/005, and optionally compares its stdout with a file.
#   run_umockdev.sh DEVICE.umockdev SCRIPT.ioctl EXPECTED|- PROGRAM [ARGS...]
# Exits 77 (ctest SKIP_RETURN_CODE) only when umockdev-run is not installed.
set -u
device=$1 script=$2 expected=$3
shift 3
if ! command -v umockdev-run >/dev/null 2>&1; then
    echo "umockdev-run not found (apt-get install umockdev): skipped"
    exit 77
fi
# umockdev's preload library comes first, which AddressSanitizer would refuse.
ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0"
export ASAN_OPTIONS
out=$(mktemp)
trap 'rm -f "$out"' EXIT
timeout 60 umockdev-run --device "$device" --ioctl /dev/bus/usb/001/005="$script" -- "$@" >"$out"
status=$?
cat "$out"
if [ $status -ne 0 ]; then
    echo "exit status $status" >&2
    exit 1
fi
if [ "$expected" != "-" ] && ! diff -u "$expected" "$out" >&2; then
    echo "output differs from $expected" >&2
    exit 1
fi
exit 0
