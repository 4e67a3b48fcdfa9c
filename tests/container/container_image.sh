#!/usr/bin/env bash
# container.image (fixture container_image): deploy/container/Containerfile
# built on the debootstrapped base with the suite's .deb (DEB_FROM=prebuilt),
# then what the image declares and holds: entrypoint, non-root user, port,
# health check, NVIDIA_DRIVER_CAPABILITIES, the NVIDIA and Mesa EGL vendor
# files, the libraries resolved, and no compiler.
#   usage: container_image.sh SOURCE_DIR BUILD_DIR WORK_DIR
source "$(dirname "$0")/lib.sh"
[ $# -eq 3 ] || fail "usage: $0 SOURCE_DIR BUILD_DIR WORK_DIR"
SRC=$1 BUILD=$2 WORK=$3
require_engine
image_names "$BUILD"
ls "$WORK"/context/deb/fluidcast_*.deb > /dev/null || fail "no .deb in $WORK/context/deb (container.deb)"

# The image this tag named before, removed once replaced (each .deb makes a new
# package layer: reruns would pile up unnamed images of about 1 GB).
previous=$("$DOCKER" image inspect -f '{{.Id}}' "$RUNTIME_IMAGE" 2> /dev/null || true)
step "build $RUNTIME_IMAGE (BASE=$BASE_IMAGE, DEB_FROM=prebuilt)"
DOCKER_BUILDKIT=${DOCKER_BUILDKIT:-1} "$DOCKER" build --network host -f "$SRC/deploy/container/Containerfile" \
    --build-arg BASE="$BASE_IMAGE" --build-arg DEB_FROM=prebuilt -t "$RUNTIME_IMAGE" "$WORK/context" \
    > "$WORK/image-build.log" 2>&1 || { tail -40 "$WORK/image-build.log"; fail "docker build failed"; }
grep -E '^#[0-9]+ (\[|DONE)' "$WORK/image-build.log" | tail -20 || true
if matches -E 'build [0-9]+/[0-9]+\] RUN cmake' "$WORK/image-build.log"; then
    fail "the build stage ran although DEB_FROM=prebuilt (no BuildKit?)"
fi

current=$("$DOCKER" image inspect -f '{{.Id}}' "$RUNTIME_IMAGE")
if [ -n "$previous" ] && [ "$previous" != "$current" ]; then
    "$DOCKER" image rm "$previous" > /dev/null 2>&1 || true
fi

step "what the image declares"
inspect() { "$DOCKER" image inspect -f "$1" "$RUNTIME_IMAGE"; }
[ "$(inspect '{{json .Config.Entrypoint}}')" = '["fluidcastd"]' ] || fail "entrypoint: $(inspect '{{json .Config.Entrypoint}}')"
[ "$(inspect '{{json .Config.Cmd}}')" = '["--listen","0.0.0.0:7450","--web-listen","0.0.0.0:8450"]' ] ||
    fail "cmd: $(inspect '{{json .Config.Cmd}}')"
[ "$(inspect '{{.Config.User}}')" = fluidcast ] || fail "user: $(inspect '{{.Config.User}}')"
inspect '{{json .Config.ExposedPorts}}' | matches -F '"7450/tcp"' || fail "port 7450 is not exposed"
inspect '{{json .Config.ExposedPorts}}' | matches -F '"8450/tcp"' || fail "the web viewer's port 8450 is not exposed"
inspect '{{json .Config.Env}}' | matches -F '"NVIDIA_DRIVER_CAPABILITIES=graphics,utility"' ||
    fail "NVIDIA_DRIVER_CAPABILITIES: $(inspect '{{json .Config.Env}}')"
inspect '{{json .Config.Healthcheck.Test}}' | matches -F '"fluidcast","info","--server","127.0.0.1:7450"' ||
    fail "health check: $(inspect '{{json .Config.Healthcheck}}')"
[ "$(inspect '{{.Config.StopSignal}}')" = SIGTERM ] || fail "stop signal: $(inspect '{{.Config.StopSignal}}')"

step "what the image holds"
"$DOCKER" run --rm --network host --entrypoint /bin/sh "$RUNTIME_IMAGE" -c '
    id -un; id -u
    sed -n "s/.*\"library_path\" *: *\"\(.*\)\".*/\1/p" /usr/share/glvnd/egl_vendor.d/10_nvidia.json
    ls /usr/share/glvnd/egl_vendor.d/
    for b in fluidcastd fluidcast; do ldd "$(command -v $b)" | grep "not found" && echo "$b: missing libraries"; done
    command -v cc gcc cmake || echo "no compiler"
    fluidcast --version' > "$WORK/image-facts.txt" 2>&1 || { cat "$WORK/image-facts.txt"; fail "the image's facts"; }
cat "$WORK/image-facts.txt"
[ "$(sed -n 1p "$WORK/image-facts.txt")" = fluidcast ] || fail "the image does not run as fluidcast"
[ "$(sed -n 2p "$WORK/image-facts.txt")" != 0 ] || fail "the image runs as uid 0"
matches -x libEGL_nvidia.so.0 "$WORK/image-facts.txt" || fail "10_nvidia.json does not name libEGL_nvidia.so.0"
matches -x 50_mesa.json "$WORK/image-facts.txt" || fail "no Mesa EGL vendor file"
if matches "missing libraries" "$WORK/image-facts.txt"; then fail "unresolved libraries"; fi
matches -x "no compiler" "$WORK/image-facts.txt" || fail "the runtime image has a compiler"
matches "^fluidcast 0\." "$WORK/image-facts.txt" || fail "fluidcast --version"
echo "image size: $(inspect '{{.Size}}') bytes"
echo "PASS"
