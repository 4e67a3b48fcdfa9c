#!/usr/bin/env bash
# Quick start, first command: set up, build, start fluidcastd locally (software GL
# when there is no GPU), render the demo scene with the CLI and say where the image is.
set -euo pipefail
cd "$(dirname "$0")/.."
deploy/setup.sh
deploy/build.sh

mkdir -p out
portfile=$(mktemp)
log=out/fluidcastd.log
build/bin/fluidcastd --listen 127.0.0.1:0 --port-file "$portfile" > "$log" 2>&1 &
daemon=$!
trap 'kill -TERM $daemon 2>/dev/null; wait $daemon 2>/dev/null; rm -f "$portfile"' EXIT

for _ in $(seq 100); do
  [ -s "$portfile" ] && break
  kill -0 $daemon 2>/dev/null || { echo "demo: fluidcastd failed to start:"; cat "$log"; exit 1; }
  sleep 0.1
done
[ -s "$portfile" ] || { echo "demo: fluidcastd did not start listening"; cat "$log"; exit 1; }
port=$(cat "$portfile")
grep -E "renderer|GL_RENDERER" "$log" | head -n 2 || true

# A sphere of water dropping into a shallow pool: 65,536 particles.
build/bin/fluidcast snapshot deploy/demo/drop_64k.f32 -o out/demo.png \
  --server "127.0.0.1:$port" --size 1280x720 \
  --eye 2.0,-2.9,1.9 --target 0,0,0.25 --up 0,0,1 --fov 40

echo "demo: wrote $(pwd)/out/demo.png"
