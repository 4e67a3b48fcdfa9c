#!/usr/bin/env bash
# container.daemon: fluidcastd in the runtime image, as an operator runs it.
#   1. `docker run` with --gpu auto and no GPU: it falls back to Mesa's
#      llvmpipe and its log says so and why.
#   2. The host's fluidcast CLI renders the analytic ball through it: a PNG
#      whose pixels show fluid where the ball projects, background elsewhere.
#   3. The image's health check (fluidcast info inside the container) turns healthy.
#   4. PID 1 is fluidcastd as user fluidcast; Mesa keeps the shaders it
#      compiled in /var/cache/fluidcast (the image's MESA_SHADER_CACHE_DIR,
#      where a volume keeps them); `docker stop` returns within 10 s
#      and the container exits 0 after the daemon logs SIGTERM.
# The container shares the host's network (the engine has no bridge; engine.sh).
#   usage: container_daemon.sh BUILD_DIR WORK_DIR FLUIDCAST_CLI BALL_TOOL
source "$(dirname "$0")/lib.sh"
[ $# -eq 4 ] || fail "usage: $0 BUILD_DIR WORK_DIR FLUIDCAST_CLI BALL_TOOL"
BUILD=$1 WORK=$2 CLI=$3 BALL=$4
require_engine
image_names "$BUILD"
"$DOCKER" image inspect "$RUNTIME_IMAGE" > /dev/null 2>&1 || fail "no image $RUNTIME_IMAGE (container.image)"
OUT=$WORK/daemon
rm -rf "$OUT"
mkdir -p "$OUT"

PORT=$(free_port)
NAME=fc-test-daemon-$$
CONTAINERS+=("$NAME")
step "docker run $RUNTIME_IMAGE --listen 127.0.0.1:$PORT --gpu auto"
"$DOCKER" run -d --name "$NAME" --network host \
    --health-cmd "fluidcast info --server 127.0.0.1:$PORT" --health-interval 1s --health-start-period 30s \
    "$RUNTIME_IMAGE" --listen "127.0.0.1:$PORT" --gpu auto > /dev/null
wait_container_port "$NAME" "$PORT" 60

step "the log: llvmpipe, and why"
"$DOCKER" logs "$NAME" > "$OUT/log.txt" 2>&1
cat "$OUT/log.txt"
matches -E "GL_RENDERER: llvmpipe" "$OUT/log.txt" || fail "the daemon does not render with llvmpipe"
matches -iE "no (GPU|hardware) EGL device.*(llvmpipe|software)" "$OUT/log.txt" ||
    fail "the log does not say why it falls back to llvmpipe"

step "the host's fluidcast renders through the container"
"$BALL" write "$OUT"
common=(--server "127.0.0.1:$PORT" --size 160x120 --eye 0,-4,0 --target 0,0,0 --radius 0.05
        --absorption "$("$BALL" absorption)")
"$CLI" snapshot "$OUT/ball.f32" -o "$OUT/ball.png" "${common[@]}"
"$CLI" snapshot "$OUT/corners.f32" -o "$OUT/empty.png" "${common[@]}"
"$BALL" check "$OUT/ball.png" "$OUT/empty.png" || fail "the picture does not show the ball"
"$CLI" info --server "127.0.0.1:$PORT" > "$OUT/info.txt"
matches -i llvmpipe "$OUT/info.txt" || fail "fluidcast info does not name llvmpipe: $(cat "$OUT/info.txt")"

step "the health check"
for _ in $(seq 1 60); do
    health=$("$DOCKER" inspect -f '{{.State.Health.Status}}' "$NAME")
    [ "$health" = healthy ] && break
    sleep 0.5
done
[ "$health" = healthy ] || fail "health: $health: $("$DOCKER" inspect -f '{{json .State.Health}}' "$NAME")"

step "PID 1 and its user"
[ "$("$DOCKER" exec "$NAME" cat /proc/1/comm)" = fluidcastd ] || fail "PID 1 is not fluidcastd"
[ "$("$DOCKER" exec "$NAME" sh -c 'stat -c %U /proc/1')" = fluidcast ] || fail "fluidcastd does not run as fluidcast"

step "the compiled shaders: in /var/cache/fluidcast, where a volume keeps them (MESA_SHADER_CACHE_DIR)"
entries=$("$DOCKER" exec "$NAME" find /var/cache/fluidcast -type f -user fluidcast | wc -l)
echo "shader cache entries: $entries"
[ "$entries" -gt 0 ] || fail "Mesa kept no compiled shader under /var/cache/fluidcast"

step "docker stop: within 10 s, exit 0"
start=$(date +%s%N)
"$DOCKER" stop -t 10 "$NAME" > /dev/null
elapsed_ms=$((($(date +%s%N) - start) / 1000000))
code=$("$DOCKER" inspect -f '{{.State.ExitCode}}' "$NAME")
"$DOCKER" logs "$NAME" > "$OUT/log.txt" 2>&1
tail -3 "$OUT/log.txt"
echo "stopped in $elapsed_ms ms, exit code $code"
[ "$elapsed_ms" -lt 10000 ] || fail "docker stop took $elapsed_ms ms (SIGKILL after 10 s?)"
[ "$code" = 0 ] || fail "the container exited $code"
matches "SIGTERM received: stopping" "$OUT/log.txt" || fail "the daemon did not log the SIGTERM"
echo "PASS"
