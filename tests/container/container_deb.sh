#!/usr/bin/env bash
# container.deb (fixture container_deb): the suite's build packed by
# `cpack -G DEB` into WORK/context/deb/, the build context of the runtime image
# (Containerfile, DEB_FROM=prebuilt) and the package the fresh-Debian install
# test installs. Needs no engine.
#   usage: container_deb.sh BUILD_DIR WORK_DIR CPACK VERSION
source "$(dirname "$0")/lib.sh"
[ $# -eq 4 ] || fail "usage: $0 BUILD_DIR WORK_DIR CPACK VERSION"
BUILD=$1 WORK=$2 CPACK=$3 VERSION=$4
DEB_DIR=$WORK/context/deb
rm -rf "$WORK/context" "$WORK/pkg"
mkdir -p "$DEB_DIR" "$WORK/pkg"
step "cpack -G DEB"
# As tests/install: without cpack's "preinstall" (make all over the tree) that
# would relink binaries other tests are running; the suite's build is complete.
(cd "$WORK" && "$CPACK" -G DEB --config "$BUILD/CPackConfig.cmake" -B "$WORK/pkg" -D CPACK_CMAKE_GENERATOR=Ninja \
    > "$WORK/cpack.log" 2>&1) || { cat "$WORK/cpack.log"; fail "cpack -G DEB failed"; }
DEB=$WORK/pkg/fluidcast_${VERSION}_$(dpkg --print-architecture).deb
[ -f "$DEB" ] || fail "no $DEB"
mv "$DEB" "$DEB_DIR/"
dpkg-deb -f "$DEB_DIR/$(basename "$DEB")" Package Version Depends
echo "PASS"
