#!/usr/bin/env bash
# reference_render.sh — a path-traced reference image of one particle frame:
# meshed and rendered by Blender Cycles as clear water in fluidcast's built-in
# scene (reference_scene.py). `reference_render.sh --help` explains; bench/LOOK.md
# says what the reference is for.
set -euo pipefail

HERE=$(cd "$(dirname "$0")" && pwd)
VTK_PYTHON=/usr/bin/python3   # reads the particles with vtk_scene.py (Debian's python3-vtk9)
export PYTHONDONTWRITEBYTECODE=1

usage() {
    cat <<EOF
usage: bench/peer/reference_render.sh FILE -o IMAGE.png --radius R --eye X,Y,Z
           --target X,Y,Z [--up X,Y,Z] [--fov DEG] [--size WxH] [options]

Meshes the particles of FILE (.ply or .f32) with Blender's geometry nodes
(Mesh to Points -> Points to Volume -> Volume to Mesh, smoothed) and renders
them with Cycles as clear water (IOR 1.33, weak absorption) under the sky, sun
and checkered floor of fluidcast's built-in scene, with the camera given,
tone-mapped as fluidcast's 8-bit images are. Give it the camera and radius the
fluidcast image was made with (bench/peer/blind_panel/make_panel.sh
--reference does).

options:
  -o, --output PNG   the image (required)
  --radius R         particle radius, as given to fluidcast (required)
  --eye, --target    camera position and point looked at (required)
  --up X,Y,Z         up direction (default 0,0,1)
  --fov DEG          vertical field of view (default 40)
  --size WxH         image size (default 960x540)
  --samples N        Cycles samples per pixel (default 32; no denoiser: more for less grain)
  --mesh-scale S     the meshing spheres' radius over R (default 2)
  --voxel-scale V    the voxel size over R (default 0.5)
  --smooth N         passes of vertex smoothing on the mesh (default 30)
  --absorption R,G,B absorption per world unit (default 0.02,0.007,0.0035 per radius)
  --threads N        render threads (default 2; the machine is shared)
  --keep-blend       also write IMAGE.png.blend, the scene, to look at in Blender
  -h, --help         this help

Needs Blender (Debian's blender 3.4: apt-get install -y blender) and, to read
the particles, VTK for /usr/bin/python3 (apt-get install -y python3-vtk9
python3-numpy). About 20-60 s for 50k particles at 960x540 on 2 cores.
Environment: STEP_TIMEOUT (seconds for the render, default 600).
EOF
}

die() { echo "reference_render: $*" >&2; exit 1; }

FILE="" OUT="" RADIUS="" EYE="" TARGET="" UP=0,0,1 FOV=40 SIZE=960x540
SAMPLES=32 MESH_SCALE=2 VOXEL_SCALE=0.5 SMOOTH=30 ABSORPTION="" THREADS=2 KEEP_BLEND=0
need_value() { [ $# -ge 2 ] || die "$1 needs a value (--help)"; }
while [ $# -gt 0 ]; do
    case $1 in
        -h|--help) usage; exit 0 ;;
        -o|--output) need_value "$@"; OUT=$2; shift 2 ;;
        --radius) need_value "$@"; RADIUS=$2; shift 2 ;;
        --eye) need_value "$@"; EYE=$2; shift 2 ;;
        --target) need_value "$@"; TARGET=$2; shift 2 ;;
        --up) need_value "$@"; UP=$2; shift 2 ;;
        --fov) need_value "$@"; FOV=$2; shift 2 ;;
        --size) need_value "$@"; SIZE=$2; shift 2 ;;
        --samples) need_value "$@"; SAMPLES=$2; shift 2 ;;
        --mesh-scale) need_value "$@"; MESH_SCALE=$2; shift 2 ;;
        --voxel-scale) need_value "$@"; VOXEL_SCALE=$2; shift 2 ;;
        --smooth) need_value "$@"; SMOOTH=$2; shift 2 ;;
        --absorption) need_value "$@"; ABSORPTION=$2; shift 2 ;;
        --threads) need_value "$@"; THREADS=$2; shift 2 ;;
        --keep-blend) KEEP_BLEND=1; shift ;;
        --*=*) set -- "${1%%=*}" "${1#*=}" "${@:2}" ;;
        -*) die "unknown option '$1' (--help)" ;;
        *) [ -z "$FILE" ] || die "one FILE only ('$FILE' and '$1')"; FILE=$1; shift ;;
    esac
done
[ -n "$FILE" ] || die "no particle FILE (--help)"
[ -r "$FILE" ] || die "$FILE: no such file (or not readable)"
[ -n "$OUT" ] || die "-o IMAGE.png is required"
[ -n "$RADIUS" ] || die "--radius is required (the radius fluidcast rendered with)"
{ [ -n "$EYE" ] && [ -n "$TARGET" ]; } || die "--eye and --target are required"
[[ $SIZE =~ ^[0-9]+[xX][0-9]+$ ]] || die "--size '$SIZE' is not WxH"
[[ $SAMPLES =~ ^[1-9][0-9]*$ ]] || die "--samples '$SAMPLES' is not a positive whole number"
[[ $THREADS =~ ^[1-9][0-9]*$ ]] || die "--threads '$THREADS' is not a positive whole number"
command -v blender >/dev/null || die "Blender missing: apt-get install -y blender (Debian's 3.4)"
(cd "$HERE" && "$VTK_PYTHON" -c 'import numpy, vtk_scene' 2>/dev/null) ||
    die "VTK or numpy missing for $VTK_PYTHON (they read the particles): apt-get install -y python3-vtk9 python3-numpy"

WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
trap 'exit 130' INT TERM

# The particles as raw float32 x y z, the one format reference_scene.py reads.
(cd "$HERE" && "$VTK_PYTHON" -c '
import sys, vtk_scene
try:
    vtk_scene.read_particles(sys.argv[1]).astype("<f4").tofile(sys.argv[2])
except vtk_scene.ParticleFileError as e:
    sys.exit(f"reference_render: {sys.argv[1]}: {e}")
' "$(cd "$(dirname "$FILE")" && pwd)/$(basename "$FILE")" "$WORK/particles.f32")

mkdir -p "$(dirname "$OUT")"
OUT=$(cd "$(dirname "$OUT")" && pwd)/$(basename "$OUT")
scene_args=(--particles "$WORK/particles.f32" --out "$OUT" --size "$SIZE" --eye="$EYE" --target="$TARGET"
            --up="$UP" --fov="$FOV" --radius "$RADIUS" --samples "$SAMPLES" --mesh-scale "$MESH_SCALE"
            --voxel-scale "$VOXEL_SCALE" --smooth "$SMOOTH" --threads "$THREADS")
[ -z "$ABSORPTION" ] || scene_args+=(--absorption="$ABSORPTION")
[ "$KEEP_BLEND" = 0 ] || scene_args+=(--blend "$OUT.blend")
if ! timeout "${STEP_TIMEOUT:-600}" blender -b --factory-startup -noaudio --python-exit-code 1 -P "$HERE/reference_scene.py" \
        -- "${scene_args[@]}" >"$WORK/blender.log" 2>&1 </dev/null; then
    tail -n 40 "$WORK/blender.log" >&2
    die "Blender failed on $FILE"
fi
grep -q '^reference_scene: ' "$WORK/blender.log" || { tail -n 40 "$WORK/blender.log" >&2; die "Blender ran no scene"; }
[ -s "$OUT" ] || { tail -n 40 "$WORK/blender.log" >&2; die "Blender wrote no $OUT"; }
grep '^reference_scene: ' "$WORK/blender.log" >&2
rm -f "$OUT.exr"
echo "$OUT"
