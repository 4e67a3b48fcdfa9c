#!/usr/bin/env bash
# container.deb_install: the .deb on a fresh Debian 12 (the debootstrapped
# base, nothing else installed), the way deploy/README.md tells a user:
# `apt-get install ./fluidcast_*.deb`, then examples/producer.c and
# tests/install/consumer built against the installed library with pkg-config
# and with CMake's find_package(fluidcast), run against the installed
# fluidcastd; then `apt-get remove`. deb_install_inside.sh runs in the container.
#   usage: container_deb_install.sh SOURCE_DIR BUILD_DIR WORK_DIR
source "$(dirname "$0")/lib.sh"
[ $# -eq 3 ] || fail "usage: $0 SOURCE_DIR BUILD_DIR WORK_DIR"
SRC=$1 BUILD=$2 WORK=$3
require_engine
image_names "$BUILD"
ls "$WORK"/context/deb/fluidcast_*.deb > /dev/null || fail "no .deb in $WORK/context/deb (container.deb)"
OUT=$WORK/deb-install
rm -rf "$OUT"
mkdir -p "$OUT"
NAME=fc-test-deb-$$
CONTAINERS+=("$NAME")
step "a fresh $BASE_IMAGE: apt-get install ./fluidcast_*.deb, build the examples, run them"
"$DOCKER" run --name "$NAME" --network host \
    -v "$WORK/context/deb:/deb:ro" -v "$SRC/examples:/src/examples:ro" \
    -v "$SRC/tests/install/consumer:/src/consumer:ro" -v "$SRC/tests/container:/src/test:ro" -v "$OUT:/out" \
    "$BASE_IMAGE" bash /src/test/deb_install_inside.sh || fail "the install on a fresh Debian 12 failed"
for f in consumer_pc.png consumer_cmake_shared.png consumer_cmake_static.png; do
    [ "$(head -c 8 "$OUT/$f" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "$f is not a PNG"
done
echo "PASS"
