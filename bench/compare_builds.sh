#!/usr/bin/env bash
# compare_builds.sh — renders the same images through two builds' fluidcastd and compares them
# pixel by pixel: the check for a change meant to leave the picture alone (shader variants,
# regions, passes merged). Every shading feature and a few cameras (horizon in view, tilted,
# below the floor), 8-bit PNG, JPEG and float EXR, the smoothed depth AOV; with SPLASH=1 also
# the 24 frames of the splash data set at the default size.
#
#   bench/compare_builds.sh OLD_BIN_DIR NEW_BIN_DIR
#
# Each BIN_DIR holds fluidcastd and fluidcast (e.g. a copy of build-bench/bin from before the
# change). Prints one line per image: identical, or oiiotool's maximum error and PSNR. Exit
# status 0 when all are identical, 1 otherwise (a change may differ on purpose; read the PSNRs).
# Needs: oiiotool (openimageio-tools), the splash data set in $DATA (default
# /work/shared/data/splash) or any .ply/.f32 file as $SCENE.
set -euo pipefail

[ $# -eq 2 ] || { echo "usage: $0 OLD_BIN_DIR NEW_BIN_DIR" >&2; exit 2; }
ROOT=$(cd "$(dirname "$0")/.." && pwd)
DATA=${DATA:-/work/shared/data/splash}
SCENE=${SCENE:-$DATA/frame_0011.ply}
RADIUS=${RADIUS:-0.0078571}
WORK=$(mktemp -d)
DAEMON_PID=""
# shellcheck disable=SC2317  # called by the EXIT trap
cleanup() {
    if [ -n "$DAEMON_PID" ]; then
        kill "$DAEMON_PID" 2>/dev/null || true
        wait "$DAEMON_PID" 2>/dev/null || true
    fi
    rm -rf "$WORK"
}
trap cleanup EXIT

# Scene images: a cube map of checkers and a gradient background.
mkdir -p "$WORK/cube"
i=0
for face in px nx py ny pz nz; do
    i=$((i + 1))
    oiiotool --pattern "checker:width=8:height=8:color1=0.$i,0.2,0.7:color2=0.9,0.$i,0.3" 64x64 3 -d uint8 \
        -o "$WORK/cube/$face.png"
done
oiiotool --pattern fill:top=0.9,0.6,0.3:bottom=0.1,0.3,0.6 320x200 3 -d uint8 -o "$WORK/background.png"
TANK=$ROOT/docs/gallery/splash_tank.obj
# shellcheck disable=SC2054  # the commas are inside values
LOW=(--eye 0.5,-1.2,0.25 --target 0.5,0.5,0.1)

render_all() {
    local bin=$1 out=$2
    mkdir -p "$out"
    "$bin/fluidcastd" --gpu software --listen 127.0.0.1:0 --port-file "$out/port" --log-level warn \
        >"$out/daemon.log" 2>&1 &
    DAEMON_PID=$!
    for _ in $(seq 100); do [ -s "$out/port" ] && break; sleep 0.1; done
    local server
    server=127.0.0.1:$(cat "$out/port")
    one() {
        local name=$1
        shift
        "$bin/fluidcast" snapshot "$SCENE" --server "$server" --size 480x360 --radius "$RADIUS" "$@" \
            -o "$out/$name" >"$out/$name.log" 2>&1 || echo "$name: render failed: $(tail -1 "$out/$name.log")"
    }
    one default.png
    one shadow_off.png --shadow off
    one noise.png --noise 1
    one foam.png --noise 1 --foam 2
    one color_by.png --color-by speed --range 0:3
    one background.png --background "$WORK/background.png"
    one cubemap.png --cubemap "$WORK/cube"
    one mesh_opaque.png --mesh "$TANK:hide-near"
    one mesh_glass.png --mesh "$TANK:hide-near:opacity=0.4"
    one mesh_shadow_off.png --mesh "$TANK:hide-near" --shadow off
    one everything.png --noise 1 --foam 2 --color-by speed --range 0:3 --cubemap "$WORK/cube" --mesh "$TANK:hide-near"
    one background_cubemap_foam.png --background "$WORK/background.png" --cubemap "$WORK/cube" --noise 1 --foam 1
    one float.exr
    one float_background_noise.exr --background "$WORK/background.png" --noise 1 --color-by density --range 900:1100
    one jpeg.jpg --noise 0.5
    one horizon.png "${LOW[@]}"
    one horizon_tilted.png --eye -0.8,-1.0,0.35 --target 0.5,0.5,0.1 --up 0.1,0,1
    one horizon_mesh.png "${LOW[@]}" --mesh "$TANK:hide-near"
    one horizon_foam.exr "${LOW[@]}" --noise 1 --foam 1 --shadow off
    one below_floor.png --eye 0.5,0.5,-0.5 --target 0.5,0.5,0.1
    # The smoothed depth itself, as floats: the default narrow-range filter (kernel from the particle size,
    # 4 passes) and the benchmarks' (3 passes, a fixed 5-pixel kernel), and the latter's colour.
    one smoothed_depth.exr --aov smoothed-depth
    one smoothed_depth_fixed.exr --aov smoothed-depth --iterations 3 --filter-radius 5
    one narrow_fixed.png --iterations 3 --filter-radius 5
    if [ "${SPLASH:-0}" = 1 ]; then
        for frame in "$DATA"/frame_*.ply; do
            "$bin/fluidcast" snapshot "$frame" --server "$server" --radius "$RADIUS" \
                -o "$out/splash_$(basename "$frame" .ply).png" >/dev/null 2>&1 || echo "$frame: render failed"
        done
    fi
    kill "$DAEMON_PID"
    wait "$DAEMON_PID" 2>/dev/null || true
    DAEMON_PID=""
}

render_all "$1" "$WORK/old"
render_all "$2" "$WORK/new"
status=0
for image in "$WORK"/old/*.png "$WORK"/old/*.exr "$WORK"/old/*.jpg; do
    name=$(basename "$image")
    report=$(oiiotool --fail 0 --warn 0 "$image" "$WORK/new/$name" --diff 2>&1 || true)
    if echo "$report" | grep -q PASS; then
        echo "$name: identical"
    else
        status=1
        echo "$name: $(echo "$report" | grep -E 'Max error|Peak SNR|over 0' | head -3 | tr -s ' \n' ' ')"
    fi
done
exit $status
