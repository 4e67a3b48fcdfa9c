#!/usr/bin/env bash
# Regenerates the README gallery through the real product path: fluidcastd on
# this machine's GL (llvmpipe without a GPU) and the fluidcast CLI, on the demo
# scene deploy/demo/drop_64k.f32 (65,536 particles) at 640x480, and on frames
# 5, 11 and 16 of the splash simulation in ../shared/data/splash (its
# suggested radius and camera, 640x360): the default (sphere kernel) | anisotropic and
# shadow off | on. The VTK | fluidcast | reference row (verdict_f*.png) comes from the blind
# panel's renders (bench/LOOK.md, "The README's triptych").
# Usage: docs/gallery/make_gallery.sh   (after deploy/build.sh)
set -euo pipefail
cd "$(dirname "$0")/../.."
out=docs/gallery
bin=build/bin
portfile=$(mktemp)
log=$(mktemp)
$bin/fluidcastd --listen 127.0.0.1:0 --port-file "$portfile" 2> "$log" &
daemon=$!
trap 'kill -TERM $daemon; wait $daemon 2>/dev/null; rm -f "$portfile" "$log"' EXIT
for _ in $(seq 100); do [ -s "$portfile" ] && break; sleep 0.1; done

snap() { # NAME ARGS...: one image through the CLI
  local name=$1; shift
  $bin/fluidcast snapshot deploy/demo/drop_64k.f32 --server "127.0.0.1:$(cat "$portfile")" --size 640x480 \
    --eye 2.0,-2.9,1.9 --target 0,0,0.25 --up 0,0,1 --fov 40 --radius 0.018 "$@" -o "$out/$name"
}
# An AOV as a viewable PNG: scaled into [0,1] (oiiotool's rangecompress-free linear map).
aov_png() { # NAME AOV SCALE
  snap "$1.exr" --aov "$2"
  oiiotool "$out/$1.exr" --mulc "$3" --clamp:min=0:max=1 -d uint8 -o "$out/$1.png"
  rm -f "$out/$1.exr"
}

for m in narrow curvature bilateral binomial none; do snap "smoothing_$m.png" --smoothing "$m"; done
snap smoothing_curvature_quarter.png --smoothing curvature --iterations 15 --smooth-scale 0.25
snap smoothing_curvature_half.png --smoothing curvature --iterations 40 --smooth-scale 0.5
snap shading_noise.png --noise 0.3
aov_png aov_depth depth 0.2
aov_png aov_smoothed_depth smoothed-depth 0.2
aov_png aov_thickness thickness 0.5
snap aov_normal.exr --aov normal
oiiotool "$out/aov_normal.exr" --mulc 0.5 --addc 0.5 --clamp:min=0:max=1 -d uint8 -o "$out/aov_normal.png"
rm -f "$out/aov_normal.exr"
splash=../shared/data/splash
if [ -d "$splash" ]; then
  for f in 05 11 16; do
    look() { # NAME ARGS...: splash frame $f as the README shows it
      local name=$1; shift
      $bin/fluidcast snapshot "$splash/frame_00$f.ply" --server "127.0.0.1:$(cat "$portfile")" --size 640x360 \
        --eye -0.3664,-1.0005,1.4229 --target 0.5,0.5,0.21 --up z --fov 40 --radius 0.0078571 "$@" \
        -o "$out/splash_f${f}_$name.png"
    }
    look sphere
    look anisotropic --kernel anisotropic
    look shadow_off --shadow off
  done
  # Frame 11's surface as a mesh extracted on the server (--surface mesh), beside the screen-space image.
  f=11
  look mesh --surface mesh
  # Per-particle radii: frame 11 with x >= 0.5 at twice the suggested radius (two_radii.py adds the column).
  two_radii=$(mktemp --suffix=.ply)
  /usr/bin/python3 docs/gallery/two_radii.py "$splash/frame_0011.ply" "$two_radii"
  $bin/fluidcast snapshot "$two_radii" --server "127.0.0.1:$(cat "$portfile")" --size 640x360 \
    --eye -0.3664,-1.0005,1.4229 --target 0.5,0.5,0.21 --up z --fov 40 -o "$out/splash_f11_two_radii.png"
  rm -f "$two_radii"
  # The splash in its tank (docs/gallery/splash_tank.obj): glass walls, and opaque ones, the near walls hidden.
  tank() { # NAME MESH-OPTIONS
    $bin/fluidcast snapshot "$splash/frame_0011.ply" --server "127.0.0.1:$(cat "$portfile")" --size 960x540 \
      --eye -0.3664,-1.0005,1.4229 --target 0.5,0.5,0.21 --up z --fov 40 --radius 0.0078571 \
      --mesh "$out/splash_tank.obj:$2" -o "$out/splash_f11_$1.png"
  }
  tank tank_glass "color=0.7,0.85,1:opacity=0.3:hide-near"
  tank tank_opaque "color=0.55,0.5,0.45:hide-near"
else
  echo "gallery: no $splash, splash rows not regenerated" >&2
fi
# The web viewer in headless chromium (puppeteer-core in build/npm-web, deploy/setup.sh), on a daemon of its own.
node docs/gallery/web_viewer.cjs $bin/fluidcastd $bin/fluidcast deploy/demo/dambreak_16k.f32 build/npm-web/node_modules \
  "$(mktemp -d)" "$out/web.png"
echo "gallery: $(ls "$out"/*.png | wc -l) images in $out"
