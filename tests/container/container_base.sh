#!/usr/bin/env bash
# container.base (fixture container_base): the Debian 12 base image, made by
# deploy/container/make_base.sh with debootstrap (minbase) and docker import;
# the tar is cached under the build tree, the image kept in the engine.
#   usage: container_base.sh SOURCE_DIR BUILD_DIR
source "$(dirname "$0")/lib.sh"
[ $# -eq 2 ] || fail "usage: $0 SOURCE_DIR BUILD_DIR"
SRC=$1 BUILD=$2
require_engine
image_names "$BUILD"
command -v debootstrap > /dev/null || fail "no debootstrap (apt-get install debootstrap; deploy/setup.sh)"

step "make_base.sh -> $BASE_IMAGE"
"$SRC/deploy/container/make_base.sh" "$BUILD/container" "$BASE_IMAGE"

step "what the base holds"
"$DOCKER" run --rm --network host "$BASE_IMAGE" sh -c '
    . /etc/os-release; echo "VERSION_ID=$VERSION_ID VERSION_CODENAME=$VERSION_CODENAME"
    echo "packages=$(dpkg-query -W | wc -l)"
    command -v apt-get; command -v cc || echo "no compiler"
    [ -e /lib/systemd/systemd ] && echo "has systemd" || echo "no systemd"' > "$BUILD/container/base-facts.txt"
cat "$BUILD/container/base-facts.txt"
matches -x "VERSION_ID=12 VERSION_CODENAME=bookworm" "$BUILD/container/base-facts.txt" || fail "the base is not Debian 12"
matches -x "no compiler" "$BUILD/container/base-facts.txt" || fail "the minbase has a compiler"
matches -x "no systemd" "$BUILD/container/base-facts.txt" || fail "the minbase has systemd"
count=$(sed -n 's/^packages=//p' "$BUILD/container/base-facts.txt")
[ "$count" -lt 150 ] || fail "$count packages: not a minbase"
echo "PASS"
