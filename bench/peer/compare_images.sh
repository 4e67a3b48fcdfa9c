#!/usr/bin/env bash
# compare_images.sh — VTK's vtkOpenGLFluidMapper and fluidcast side by side on the
# same particles, camera, image size, radius and background, one PNG per frame.
# `compare_images.sh --help` explains; docs/benchmarks.md ("Side by side with VTK") shows it.
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/../.." && pwd)
PEER_DIR=$ROOT/bench/peer
VTK_PYTHON=/usr/bin/python3   # Debian's: python3-vtk9 is not in other interpreters
export PYTHONDONTWRITEBYTECODE=1  # no __pycache__ in the source tree
STEP_TIMEOUT=${STEP_TIMEOUT:-600}
TOP=$(git -C "$ROOT" rev-parse --show-toplevel 2>/dev/null || echo "$ROOT")
SPLASH=$(cd "$TOP/.." && pwd)/shared/data/splash

usage() {
    cat <<EOF
usage: bench/peer/compare_images.sh [options] [FILE...] [-- SNAPSHOT_ARGS...]

Renders each particle FILE with VTK's vtkOpenGLFluidMapper (narrow-range filter,
transparent fluid volume, VTK's water example values: attenuation colour
0.8,0.2,0.15, scale 1, IOR 1.33) and with fluidcast (\`fluidcast snapshot\`,
its own shading, --ior 1.33), with the same camera, image size and particle
radius, and writes one PNG per frame: VTK left, fluidcast right, a caption
strip above.

Both see the same scene behind the fluid: VTK renders a checkered floor plane
(at z = 0 for the splash data, else at the lowest particle; +z is up) under a
sky gradient without the fluid once, to OUT/floor.png, and fluidcast gets that
image as --background, so only the fluid differs.

Without FILEs: frames 5, 11 and 16 of the splash data set,
$SPLASH (see its README.md).
The VTK side reads .ply (binary little-endian, x y z among the vertex
properties) and .f32 (float32 x y z) only; fluidcast also reads .vtk and .csv:
convert those first.

options:
  --out DIR         output directory (default out/compare, under the current
                    directory); it gets floor.png, vtk_NNNN.png, fc_NNNN.png
                    and compare_NNNN.png, NNNN the frame number
  --size WxH        image size of each half (default 960x540)
  --radius R        particle radius (default: the splash's suggested radius
                    0.0078571 for splash frames, else the radius fluidcast
                    estimates for the first file, used for every file)
  --eye X,Y,Z       camera position      \\  default: the splash camera of
  --target X,Y,Z    point looked at       | frames.json for splash frames,
  --up X,Y,Z        up direction          | else a 3/4 view from -x,-y that
  --fov DEG         vertical field of view / frames the particles' bounding box
  --server HOST:PORT  a running fluidcastd (default: start build/bin/fluidcastd
                    on a free loopback port and stop it at the end)
  --bin-dir DIR     where fluidcast and fluidcastd are (default $ROOT/build/bin)
  -h, --help        this help
  -- ARGS           the rest goes to every \`fluidcast snapshot\` (compare
                    settings: -- --smoothing curvature --iterations 40);
                    camera, size, radius, background, output and server are
                    this script's options, so that VTK gets them too

Needs python3-vtk9, python3-numpy, and xvfb + xauth without \$DISPLAY (Debian
packages: deploy/setup.sh --bench installs them), and a built fluidcast.
Environment: STEP_TIMEOUT (seconds for any one step, default 600).
EOF
}

die() { echo "compare_images: $*" >&2; exit 1; }
log() { echo "compare_images: $*" >&2; }

OUT=out/compare
SIZE=960x540
RADIUS_OPT=""
EYE_OPT="" TARGET_OPT="" UP_OPT="" FOV_OPT=""
SERVER=""
BIN_DIR=$ROOT/build/bin
FILES=()
PASS=()

need_value() { [ $# -ge 2 ] || die "$1 needs a value (--help)"; }
while [ $# -gt 0 ]; do
    case $1 in
        -h|--help) usage; exit 0 ;;
        --out) need_value "$@"; OUT=$2; shift 2 ;;
        --size) need_value "$@"; SIZE=$2; shift 2 ;;
        --radius) need_value "$@"; RADIUS_OPT=$2; shift 2 ;;
        --eye) need_value "$@"; EYE_OPT=$2; shift 2 ;;
        --target) need_value "$@"; TARGET_OPT=$2; shift 2 ;;
        --up) need_value "$@"; UP_OPT=$2; shift 2 ;;
        --fov) need_value "$@"; FOV_OPT=$2; shift 2 ;;
        --server) need_value "$@"; SERVER=$2; shift 2 ;;
        --bin-dir) need_value "$@"; BIN_DIR=$2; shift 2 ;;
        --out=*|--size=*|--radius=*|--eye=*|--target=*|--up=*|--fov=*|--server=*|--bin-dir=*)
            set -- "${1%%=*}" "${1#*=}" "${@:2}" ;;
        --) shift; PASS=("$@"); break ;;
        -*) die "unknown option '$1' (--help; fluidcast's own options go after --)" ;;
        *) FILES+=("$1"); shift ;;
    esac
done

for arg in ${PASS[@]+"${PASS[@]}"}; do
    case $arg in
        -o|--output|--output=*|--size|--size=*|--eye|--eye=*|--target|--target=*|--up|--up=*|\
        --fov|--fov=*|--radius|--radius=*|--background|--background=*|--server|--server=*|--aov|--aov=*)
            die "'$arg' after --: use this script's option instead, so that VTK gets it too" ;;
    esac
done

if [ ${#FILES[@]} -eq 0 ]; then
    for frame in 5 11 16; do
        FILES+=("$SPLASH/$(printf 'frame_%04d.ply' "$frame")")
    done
fi
for f in "${FILES[@]}"; do
    [ -r "$f" ] || die "$f: no such file (or not readable)"
    case ${f,,} in
        *.ply|*.f32) ;;
        *) die "$f: the VTK side reads .ply and .f32 only (fluidcast also reads .vtk and .csv: convert those)" ;;
    esac
done

# --- prerequisites ---
FLUIDCAST=$BIN_DIR/fluidcast
[ -x "$FLUIDCAST" ] || die "$FLUIDCAST missing: build fluidcast first (cmake -S . -B build && cmake --build build), or --bin-dir"
"$VTK_PYTHON" -c 'import numpy, vtkmodules.vtkRenderingOpenGL2' 2>/dev/null ||
    die "VTK or numpy missing for $VTK_PYTHON: run deploy/setup.sh --bench (python3-vtk9 python3-numpy)"
if [ -n "${DISPLAY:-}" ]; then
    run_vtk() { timeout "$STEP_TIMEOUT" "$VTK_PYTHON" "$PEER_DIR/vtk_fluid_image.py" "$@"; }
else
    if ! command -v xvfb-run >/dev/null || ! command -v xauth >/dev/null; then
        die "no \$DISPLAY and no xvfb-run/xauth for VTK: run deploy/setup.sh --bench (xvfb xauth)"
    fi
    run_vtk() {
        timeout "$STEP_TIMEOUT" xvfb-run -a env LIBGL_ALWAYS_SOFTWARE=1 \
            "$VTK_PYTHON" "$PEER_DIR/vtk_fluid_image.py" "$@"
    }
fi

mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
WORK=$(mktemp -d)
DAEMON_PID=""
cleanup() {
    if [ -n "$DAEMON_PID" ]; then
        kill "$DAEMON_PID" 2>/dev/null || true
        wait "$DAEMON_PID" 2>/dev/null || true
    fi
    rm -rf "$WORK"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# --- 1. VTK: camera, floor, floor.png (the scene without the fluid) ---
scene_args=(--out "$OUT" --size "$SIZE")
[ -z "$RADIUS_OPT" ] || scene_args+=(--radius "$RADIUS_OPT")
[ -z "$EYE_OPT" ] || scene_args+=(--eye "$EYE_OPT")
[ -z "$TARGET_OPT" ] || scene_args+=(--target "$TARGET_OPT")
[ -z "$UP_OPT" ] || scene_args+=(--up "$UP_OPT")
[ -z "$FOV_OPT" ] || scene_args+=(--fov "$FOV_OPT")
log "VTK: floor and sky without the fluid"
run_vtk scene "${scene_args[@]}" -- "${FILES[@]}" >/dev/null || die "VTK scene step failed"
EYE="" TARGET="" UP="" FOV="" RADIUS="" FLOOR="" FRAMES=""
# shellcheck source=/dev/null
. "$OUT/scene.env"

# --- 2. fluidcast, with floor.png behind the fluid ---
if [ -z "$SERVER" ]; then
    FLUIDCASTD=$BIN_DIR/fluidcastd
    [ -x "$FLUIDCASTD" ] || die "$FLUIDCASTD missing: build it, or give --server"
    "$FLUIDCASTD" --listen 127.0.0.1:0 --port-file "$WORK/port" --log-level warn 2>"$WORK/daemon.log" &
    DAEMON_PID=$!
    for _ in $(seq 200); do
        [ -s "$WORK/port" ] && break
        kill -0 "$DAEMON_PID" 2>/dev/null || { cat "$WORK/daemon.log" >&2; die "fluidcastd exited"; }
        sleep 0.1
    done
    [ -s "$WORK/port" ] || die "fluidcastd did not report its port within 20 s"
    SERVER=127.0.0.1:$(cat "$WORK/port")
    log "started fluidcastd (pid $DAEMON_PID) on $SERVER"
fi

while IFS=$'\t' read -r tag file; do
    snapshot=("$FLUIDCAST" snapshot "$file" -o "$OUT/fc_$tag.png" --server "$SERVER" --size "$SIZE"
              --eye "$EYE" --target "$TARGET" --up "$UP" --fov "$FOV" --background "$FLOOR"
              --ior 1.33)
    [ -z "$RADIUS" ] || snapshot+=(--radius "$RADIUS")
    snapshot+=(${PASS[@]+"${PASS[@]}"})
    log "fluidcast: $file"
    if ! timeout "$STEP_TIMEOUT" "${snapshot[@]}" </dev/null >"$WORK/snapshot.out" 2>&1; then
        cat "$WORK/snapshot.out" >&2
        die "fluidcast snapshot failed on $file"
    fi
    cat "$WORK/snapshot.out" >&2
    if [ -z "$RADIUS" ]; then   # the first file's estimate, for VTK and the other files
        RADIUS=$(sed -n 's/.*radius \([0-9.eE+-]*\) (estimated.*/\1/p' "$WORK/snapshot.out")
        [ -n "$RADIUS" ] || die "no 'radius R (estimated ...)' in fluidcast's output; give --radius"
        log "radius $RADIUS (fluidcast's estimate for $file)"
    fi
done <"$FRAMES"

# --- 3. VTK with the fluid, and the side-by-side images ---
log "VTK: the fluid, and composing"
run_vtk render --out "$OUT" --radius "$RADIUS" >"$WORK/render.out" || die "VTK render step failed"
echo "$OUT/floor.png"
grep '/compare_' "$WORK/render.out"
