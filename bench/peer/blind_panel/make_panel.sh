#!/usr/bin/env bash
# make_panel.sh — a blind panel: VTK's fluid mapper and fluidcast on the same
# frames, as randomised "A | B" pairs, a brief for the judges, and a key kept
# apart. `make_panel.sh --help` explains; bench/LOOK.md says how to run a panel.
set -euo pipefail

HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../../.." && pwd)
VTK_PYTHON=/usr/bin/python3   # Debian's: python3-vtk9 is not in other interpreters
export PYTHONDONTWRITEBYTECODE=1  # no __pycache__ in the source tree

usage() {
    cat <<EOF
usage: bench/peer/blind_panel/make_panel.sh [options] FILE...
       bench/peer/blind_panel/make_panel.sh --sweep [options] FILE...

Renders each particle FILE (.ply or .f32) three ways, with one camera and image
size per data set:
  vtk         VTK's vtkOpenGLFluidMapper over its checkered floor and sky, at
              its best settings for the data set (vtk_best.tsv: a radius scale
              over the data's suggested radius, and the filter;
              bench/LOOK.md says how they were chosen)
  fc_floor    fluidcast over VTK's floor image (--background): only the fluid differs
  fc_builtin  fluidcast in its own built-in scene (checker floor, sky, sun)
and composes, for each frame and comparison, one pair image: two renders side
by side labelled only "A" and "B", sides and order shuffled from --seed.

  OUT/pairs/      pair_NN.png and BRIEF.md (judge_brief.md): give judges this folder
  OUT/key.tsv     seed, and which condition is A and B in each pair (keep it from judges)
  OUT/renders/    every render, named by what made it

Score the answers with bench/peer/blind_panel/score.py OUT/key.tsv ANSWERS...
The same FILEs, options and seed give the same panel again.

--sweep renders VTK alone at radius scales x filters into OUT/sweep/
(the sweep that chose vtk_best.tsv).

options:
  --out DIR          output directory (required; keep it out of the repository)
  --seed N           randomisation seed (default: a new one, printed and kept in the key)
  --size WxH         size of each render (default 960x540)
  --comparisons L    pairs to make per frame, X:Y,... of vtk, fc_floor, fc_builtin
                     (default vtk:fc_floor,vtk:fc_builtin)
  --reference        add the path-traced reference (bench/peer/reference_render.sh,
                     Blender Cycles) as a third image, "Reference", to every pair
  --reuse-renders    keep the renders already in OUT/renders instead of making
                     them again (only for the same files and options: a rerun
                     with --reference then renders the references alone)
  --radius R         base particle radius (default: the data set's suggestion:
                     the splash's frames.json, gen_particles.py's .json, else
                     fluidcast's estimate); VTK gets R times its scale
  --eye X,Y,Z --target X,Y,Z --up X,Y,Z --fov DEG
                     camera (default: the splash camera for splash frames, else
                     a 3/4 view framing the particles, as compare_images.sh)
  --floor checker|soft|plain
                     VTK's floor texture, which fc_floor gets as its background
                     (default checker: the high-contrast squares, over which
                     VTK's bumpy surface refracts into moire; soft: the same
                     squares at a quarter of the contrast; plain: their mean
                     colour; bench/LOOK.md says which floor a verdict uses)
  --vtk-scale S --vtk-filter narrow|bilateral
                     override vtk_best.tsv for every data set
  --server HOST:PORT a running fluidcastd (default: start build/bin/fluidcastd)
  --bin-dir DIR      where fluidcast and fluidcastd are (default $ROOT/build/bin)
  --scales L --filters L
                     with --sweep: radius scales (default 1,1.5,2,3) and
                     filters (default narrow,bilateral)
  -- ARGS            the rest goes to every \`fluidcast snapshot\`
  -h, --help         this help

Needs VTK for Debian's /usr/bin/python3 (apt-get install -y python3-vtk9
python3-numpy, or deploy/setup.sh --bench), xvfb-run and xauth without
\$DISPLAY, a built fluidcast and fluidcastd, and for --reference Blender
(apt-get install -y blender). Renders run one at a time.
Environment: STEP_TIMEOUT (seconds for any one render, default 600).
EOF
}

die() { echo "make_panel: $*" >&2; exit 1; }
log() { echo "make_panel: $*" >&2; }

OUT="" SEED="" SERVER="" SWEEP=0
BIN_DIR=$ROOT/build/bin
PANEL_ARGS=() SWEEP_ARGS=() FILES=() PASS=()
need_value() { [ $# -ge 2 ] || die "$1 needs a value (--help)"; }
while [ $# -gt 0 ]; do
    case $1 in
        -h|--help) usage; exit 0 ;;
        --sweep) SWEEP=1; shift ;;
        --reference|--reuse-renders) PANEL_ARGS+=("$1"); shift ;;
        --out) need_value "$@"; OUT=$2; shift 2 ;;
        --seed) need_value "$@"; SEED=$2; shift 2 ;;
        --server) need_value "$@"; SERVER=$2; shift 2 ;;
        --bin-dir) need_value "$@"; BIN_DIR=$2; shift 2 ;;
        --size|--radius|--eye|--target|--up|--fov|--floor)
            need_value "$@"; PANEL_ARGS+=("$1" "$2"); SWEEP_ARGS+=("$1" "$2"); shift 2 ;;
        --comparisons|--vtk-scale|--vtk-filter)
            need_value "$@"; PANEL_ARGS+=("$1" "$2"); shift 2 ;;
        --scales|--filters)
            need_value "$@"; SWEEP_ARGS+=("$1" "$2"); shift 2 ;;
        --*=*) set -- "${1%%=*}" "${1#*=}" "${@:2}" ;;
        --) shift; PASS=("$@"); break ;;
        -*) die "unknown option '$1' (--help; fluidcast's own options go after --)" ;;
        *) FILES+=("$1"); shift ;;
    esac
done
[ -n "$OUT" ] || die "--out DIR is required (--help)"
[ ${#FILES[@]} -gt 0 ] || die "no particle FILE given (--help)"
for f in "${FILES[@]}"; do
    [ -r "$f" ] || die "$f: no such file (or not readable)"
    case ${f,,} in
        *.ply|*.f32) ;;
        *) die "$f: the VTK side reads .ply and .f32 only (convert other formats)" ;;
    esac
done
if [ -n "$SEED" ]; then
    [[ $SEED =~ ^[0-9]+$ ]] || die "--seed '$SEED' is not a whole number"
else
    SEED=$(od -An -N4 -tu4 /dev/urandom | tr -d ' ')
fi

# --- prerequisites ---
"$VTK_PYTHON" -c 'import numpy, vtkmodules.vtkRenderingOpenGL2' 2>/dev/null ||
    die "VTK or numpy missing for $VTK_PYTHON: apt-get install -y python3-vtk9 python3-numpy (or deploy/setup.sh --bench)"
if [ -n "${DISPLAY:-}" ]; then
    run_panel() { "$VTK_PYTHON" "$HERE/panel.py" "$@"; }
else
    { command -v xvfb-run >/dev/null && command -v xauth >/dev/null; } ||
        die "no \$DISPLAY and no xvfb-run/xauth for VTK: apt-get install -y xvfb xauth"
    run_panel() { xvfb-run -a env LIBGL_ALWAYS_SOFTWARE=1 "$VTK_PYTHON" "$HERE/panel.py" "$@"; }
fi
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)

if [ "$SWEEP" = 1 ]; then
    run_panel sweep --out "$OUT" ${SWEEP_ARGS[@]+"${SWEEP_ARGS[@]}"} -- "${FILES[@]}"
    exit 0
fi

FLUIDCAST=$BIN_DIR/fluidcast
[ -x "$FLUIDCAST" ] || die "$FLUIDCAST missing: build fluidcast first (cmake --build build), or --bin-dir"
for arg in ${PANEL_ARGS[@]+"${PANEL_ARGS[@]}"}; do
    [ "$arg" != --reference ] || command -v blender >/dev/null ||
        die "--reference needs Blender: apt-get install -y blender"
done
for arg in ${PASS[@]+"${PASS[@]}"}; do
    case $arg in
        -o|--output*|--size*|--eye*|--target*|--up*|--fov*|--radius*|--background*|--server*)
            die "'$arg' after --: use this script's option instead, so that every render gets it" ;;
    esac
done

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

log "seed $SEED"
run_panel pairs --out "$OUT" --seed "$SEED" --fluidcast "$FLUIDCAST" --server "$SERVER" \
    --fluidcast-args="${PASS[*]+${PASS[*]}}" ${PANEL_ARGS[@]+"${PANEL_ARGS[@]}"} -- "${FILES[@]}"
