#!/usr/bin/env bash
# mesh_vs_openvdb.sh — fluidcast's surface meshes against OpenVDB's (issue 27), in one
# run on one machine: each frame meshed by fluidcastd (Client.mesh) and by OpenVDB's
# ParticlesToLevelSet + VolumeToMesh (mesh_openvdb.cpp, Debian's libopenvdb-dev) at the
# same cell size, then the time, the triangles and the two meshes' distance (nearest
# vertex, both ways) as a markdown table. `mesh_vs_openvdb.sh --help` explains.
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/../.." && pwd)
PEER_DIR=$ROOT/bench/peer
PYTHON=/usr/bin/python3   # Debian's, with numpy
export PYTHONDONTWRITEBYTECODE=1
TOP=$(git -C "$ROOT" rev-parse --show-toplevel 2>/dev/null || echo "$ROOT")
DATA=$(cd "$TOP/.." && pwd)/shared/data

usage() {
    cat <<USAGE
usage: bench/peer/mesh_vs_openvdb.sh [options] [FILE.f32...]

Meshes each FILE (float32 x y z) with fluidcastd and with OpenVDB at cells of
CELL particle radii (for OpenVDB: voxels of CELL x RADIUS, spheres of
(1 + GROW) x RADIUS, the level set then offset inwards by GROW x RADIUS), and
prints one table row per file, cell and GROW: particles, time and triangles of
each, and the mean and largest distance from each mesh's vertices to the
other's nearest vertex, in particle radii. GROW 1 is how an OpenVDB user gets a
closed surface of fluid at rest (spheres of the solver's radius, half the
spacing, leave a cavity in every lattice cube: GROW 0 meshes that sponge).

Without FILEs: $DATA/dambreak_16k.f32 and dambreak_64k.f32
(RADIUS: their .json's particle_radius).

options:
  --cells "C..."      cell sizes in particle radii (default "0.5 1 1.5")
  --radius R          particle radius (default: the file's .json particle_radius)
  --grow "G..."       OpenVDB's sphere growths, each a row (default "1 0")
  --out DIR           meshes and the program (default out/mesh_vs_openvdb)
  --server HOST:PORT  a running fluidcastd (default: start build/bin/fluidcastd
                      on a free loopback port and stop it at the end)
  --bin-dir DIR       where fluidcastd and libfluidcast are (default $ROOT/build)
  -h, --help          this help

Needs g++, libopenvdb-dev (deploy/setup.sh --bench), python3-numpy and a build.
USAGE
}

CELLS="0.5 1 1.5" GROWS="1 0" RADIUS="" OUT=out/mesh_vs_openvdb SERVER="" BUILD=$ROOT/build FILES=()
while [ $# -gt 0 ]; do
    case $1 in
    --cells) CELLS=$2; shift 2 ;;
    --radius) RADIUS=$2; shift 2 ;;
    --grow) GROWS=$2; shift 2 ;;
    --out) OUT=$2; shift 2 ;;
    --server) SERVER=$2; shift 2 ;;
    --bin-dir) BUILD=$2; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    -*) echo "mesh_vs_openvdb.sh: unknown option $1" >&2; exit 2 ;;
    *) FILES+=("$1"); shift ;;
    esac
done
[ ${#FILES[@]} -gt 0 ] || FILES=("$DATA/dambreak_16k.f32" "$DATA/dambreak_64k.f32")
mkdir -p "$OUT"

VDB=$OUT/mesh_openvdb
if [ ! -x "$VDB" ] || [ "$PEER_DIR/mesh_openvdb.cpp" -nt "$VDB" ]; then
    echo "building $VDB (OpenVDB $(dpkg-query -W -f='${Version}' libopenvdb-dev 2>/dev/null || echo '?'))" >&2
    # pkg-config's flags as words (its output ends in a space, which one quoted argument would keep).
    read -ra IMATH_LIBS < <(pkg-config --libs Imath 2>/dev/null || echo -lImath-3_1)
    g++ -std=c++17 -O2 -o "$VDB" "$PEER_DIR/mesh_openvdb.cpp" -lopenvdb -ltbb "${IMATH_LIBS[@]}"
fi

DAEMON_PID=""
cleanup() { [ -z "$DAEMON_PID" ] || kill "$DAEMON_PID" 2>/dev/null || true; }
trap cleanup EXIT
if [ -z "$SERVER" ]; then
    rm -f "$OUT/port"
    "$BUILD/bin/fluidcastd" --listen 127.0.0.1:0 --port-file "$OUT/port" >"$OUT/fluidcastd.log" 2>&1 &
    DAEMON_PID=$!
    for _ in $(seq 100); do [ -s "$OUT/port" ] && break; sleep 0.2; done
    [ -s "$OUT/port" ] || { echo "fluidcastd did not start: $OUT/fluidcastd.log" >&2; exit 1; }
    SERVER=127.0.0.1:$(cat "$OUT/port")
fi

radius_of() {
    [ -n "$RADIUS" ] && { echo "$RADIUS"; return; }
    "$PYTHON" -c 'import json,sys; print(json.load(open(sys.argv[1]))["particle_radius"])' "${1%.f32}.json"
}

echo "| frame | particles | cell (× r) | OpenVDB spheres (× r) | fluidcast s | fluidcast triangles | OpenVDB s | OpenVDB triangles | fluidcast / OpenVDB time | distance mean (× r) | distance max (× r) |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for file in "${FILES[@]}"; do
    r=$(radius_of "$file")
    name=$(basename "$file" .f32)
    for cell in $CELLS; do
        fc=$OUT/${name}_${cell}_fluidcast.ply
        fc_line=$(LD_LIBRARY_PATH=$BUILD/lib PYTHONPATH=$ROOT/python FLUIDCAST_LIBRARY=$BUILD/lib/libfluidcast.so \
                  "$PYTHON" "$PEER_DIR/mesh_fluidcast.py" "$SERVER" "$file" "$r" "$cell" "$fc")
        vdb_cell=$("$PYTHON" -c "print($cell * $r)")
        for grow in $GROWS; do
            vdb=$OUT/${name}_${cell}_openvdb_grow${grow}.ply
            vdb_line=$("$VDB" mesh "$file" "$r" "$vdb_cell" "$vdb" "$grow")
            dist_line=$("$VDB" distance "$fc" "$vdb")
            echo "$fc_line; grow $grow: $vdb_line; $dist_line" >&2
            "$PYTHON" - "$name" "$cell" "$grow" "$r" "$fc_line" "$vdb_line" "$dist_line" <<'ROW'
import re, sys
name, cell, grow, r, fc, vdb, dist = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), *sys.argv[5:]
def parse(line):
    m = re.match(r"\w+: (\d+) particles, (\d+) triangles, ([0-9.]+) s", line)
    return int(m.group(1)), int(m.group(2)), float(m.group(3))
n, fc_t, fc_s = parse(fc)
_, vdb_t, vdb_s = parse(vdb)
mean, largest = (float(x) for x in re.match(r"distance: mean (\S+) max (\S+)", dist).groups())
spheres = "%g, offset by -%g" % (1 + grow, grow) if grow > 0 else "1"
print("| %s | %d | %s | %s | %.3f | %d | %.3f | %d | %.2f | %.2f | %.2f |"
      % (name, n, cell, spheres, fc_s, fc_t, vdb_s, vdb_t, fc_s / vdb_s, mean / r, largest / r))
ROW
        done
    done
done
