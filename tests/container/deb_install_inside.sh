#!/usr/bin/env bash
# Runs inside a fresh Debian 12 container (container_deb_install.sh): /deb holds
# the .deb, /src/examples and /src/consumer the sources to build, /out
# receives the images. Installs, builds, renders, removes.
set -euo pipefail
step() { echo "== $(date +%T) $*"; }
fail() { echo "FAIL (in the container): $*" >&2; exit 1; }
export DEBIAN_FRONTEND=noninteractive
DAEMON_PID=""
trap '[ -z "$DAEMON_PID" ] || kill "$DAEMON_PID" 2>/dev/null || true' EXIT

step "apt-get install ./fluidcast_*.deb"
apt-get update -qq
cd /deb
apt-get install -y -q ./fluidcast_*.deb > /out/apt-install.log 2>&1 || { tail -30 /out/apt-install.log; fail "apt-get install"; }
grep -E '^(Setting up|Unpacking) fluidcast ' /out/apt-install.log
dpkg-query -W -f='${Package} ${Version} ${Status}\n' fluidcast | grep -q "install ok installed" || fail "fluidcast is not installed"
command -v fluidcastd fluidcast
fluidcast --version

step "a compiler, pkg-config, CMake (and libzstd-dev, libssl-dev for the static library)"
apt-get install -y -q --no-install-recommends gcc libc6-dev make pkg-config cmake libzstd-dev libssl-dev > /out/apt-tools.log 2>&1 ||
    { tail -30 /out/apt-tools.log; fail "apt-get install of the tools"; }

B=/tmp/build
mkdir -p $B
step "pkg-config: $(pkg-config --cflags --libs fluidcast)"
# shellcheck disable=SC2046
cc -std=c11 -Wall -Wextra -Werror -D_POSIX_C_SOURCE=200809L -o $B/consumer_pc /src/consumer/consumer.c \
    $(pkg-config --cflags --libs fluidcast) -lm
# shellcheck disable=SC2046
cc -std=c11 -Wall -Wextra -Werror -D_POSIX_C_SOURCE=200809L -o $B/producer_pc /src/examples/producer.c \
    /src/examples/sloshing_block.c $(pkg-config --cflags --libs fluidcast) -lm

step "CMake: find_package(fluidcast) with no hints"
cmake -S /src/consumer -B $B/cmake -DFC_EXAMPLES_DIR=/src/examples > $B/cmake.log || { cat $B/cmake.log; fail "cmake configure"; }
grep fluidcast_DIR $B/cmake/CMakeCache.txt
cmake --build $B/cmake -j2 > $B/cmake-build.log || { cat $B/cmake-build.log; fail "cmake build"; }

step "the installed fluidcastd renders for them"
fluidcastd --listen 127.0.0.1:0 --port-file $B/port --gpu software --log-level warn &
DAEMON_PID=$!
for _ in $(seq 1 300); do [ -s $B/port ] && break; sleep 0.1; done
[ -s $B/port ] || fail "fluidcastd did not announce its port"
ADDR=127.0.0.1:$(cat $B/port)
$B/consumer_pc "$ADDR" /out/consumer_pc.png
$B/cmake/consumer_shared "$ADDR" /out/consumer_cmake_shared.png
$B/cmake/consumer_static "$ADDR" /out/consumer_cmake_static.png
$B/producer_pc "$ADDR" deb-install-pc 3
$B/cmake/producer_shared "$ADDR" deb-install-cmake 3
kill "$DAEMON_PID"
wait "$DAEMON_PID" || fail "fluidcastd exited $? on SIGTERM"
DAEMON_PID=""

step "apt-get remove fluidcast"
apt-get remove -y -q fluidcast > /out/apt-remove.log 2>&1 || { cat /out/apt-remove.log; fail "apt-get remove"; }
if command -v fluidcastd; then fail "fluidcastd is still there after apt-get remove"; fi
chmod -R a+rwX /out
echo "inside: PASS"
