#!/usr/bin/env bash
# test_compare_images.sh COMPARE_SCRIPT BIN_DIR SPLASH_FRAME OUT_DIR
# Runs bench/peer/compare_images.sh on one splash frame at 480x270 and checks its
# images (check_compare_images.py). Exit 77 (skip) when VTK, numpy, an X server
# (xvfb-run or $DISPLAY) or the splash frame is missing.
set -euo pipefail
[ $# -eq 4 ] || { echo "usage: $0 COMPARE_SCRIPT BIN_DIR SPLASH_FRAME OUT_DIR" >&2; exit 2; }
script=$1 bin_dir=$2 frame=$3 out=$4
here=$(cd "$(dirname "$0")" && pwd)
export PYTHONDONTWRITEBYTECODE=1  # no __pycache__ in the source tree

skip() { echo "SKIP: $*"; exit 77; }
/usr/bin/python3 -c 'import numpy, vtkmodules.vtkRenderingOpenGL2' 2>/dev/null ||
    skip "python3-vtk9 or python3-numpy missing (deploy/setup.sh --bench)"
[ -n "${DISPLAY:-}" ] || { command -v xvfb-run >/dev/null && command -v xauth >/dev/null; } ||
    skip "no \$DISPLAY and no xvfb-run/xauth (deploy/setup.sh --bench)"
[ -r "$frame" ] || skip "splash data not found: $frame"

rm -rf "$out"
"$script" --bin-dir "$bin_dir" --out "$out" --size 480x270 "$frame" >"$out.stdout"
cat "$out.stdout"
grep -qx "$out/compare_0011.png" "$out.stdout" || { echo "FAIL: compare_0011.png not among the paths printed"; exit 1; }
grep -qx "$out/floor.png" "$out.stdout" || { echo "FAIL: floor.png not among the paths printed"; exit 1; }
/usr/bin/python3 "$here/check_compare_images.py" "$out" 0011
