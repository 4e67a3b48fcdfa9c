#!/usr/bin/env bash
# Installs every Debian 12 package fluidcast needs to build, test and run the demo.
# Idempotent: installs only what is missing. Needs root (uses sudo when not root).
set -euo pipefail

PACKAGES=(
  # toolchain
  build-essential cmake pkg-config git
  # cpack -G DEB (tests/install, tests/container): dpkg-shlibdeps runs file(1)
  file
  # GL through EGL with no display, software rasterizer (llvmpipe) where there is no GPU
  libepoxy-dev libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  # image encoding
  libopenimageio-dev
  # compressed frame uploads
  libzstd-dev
  # TLS on TCP connections (OpenSSL 3), and the openssl tool tests/tls makes its certificates with
  libssl-dev openssl
  # particle readers: gzip'd .bgeo and compressed .vtu (zlib), VTK XML (expat)
  zlib1g-dev libexpat1-dev
  # HDF5 particle files (libhdf5), and h5py to write the reader tests' files with the real tool
  libhdf5-dev python3-h5py
  # fluidcast snapshot --legend: text with FreeType and a DejaVu font
  libfreetype-dev fonts-dejavu-core
  # fluidcast render to .mp4/.webm (libavcodec with libx264 and libvpx); fluidcastd's H.264 streams
  libavcodec-dev libavformat-dev libavutil-dev libswscale-dev
  # fluidcast render --camera-path: the camera keyframe file (JSON)
  libcjson-dev
  # shader validation in the test suite
  glslang-tools
  # fuzzing (libFuzzer) in the test suite
  clang-14 libclang-rt-14-dev
  # SpaceMouse over USB; its tests replay scripted devices under umockdev
  libusb-1.0-0-dev umockdev libumockdev-dev
  # fluidcast view: its SDL2 window; its tests run it under xvfb-run
  libsdl2-dev xvfb xauth
  # fluidcastd under systemd (sd_notify, socket activation; systemd-analyze checks the units)
  # and its /metrics endpoint (libmicrohttpd; promtool checks the output)
  libsystemd-dev systemd libmicrohttpd-dev prometheus
  # its web viewer (--web-listen: libwebsockets), tested in Debian's headless chromium (tests/web)
  libwebsockets-dev chromium
  # the HTTPS test trusts its own CA in a private NSS database, as a user would (certutil)
  libnss3-tools
  # the Python binding (python/fluidcast) and its tests under Debian's python3
  python3-numpy python3-pytest
  # "srv:" addresses: a real DNS server (dnsmasq, its binary alone) serves SRV records in tests/srv
  dnsmasq-base
  # deploy/slurm's batch scripts run on a one-host Slurm cluster in the tests (tests/slurm,
  # deploy/slurm/test-cluster.sh): its daemons, munge, and ss to pick free ports
  slurm-wlm munge iproute2
  # deploy/kubernetes/validate.cjs runs under Node.js (its npm packages: below)
  nodejs
  # the container image and the .deb on a fresh Debian 12 (ctest -L container): Debian's
  # docker engine (dockerd, containerd, runc; deploy/container/engine.sh starts it) and
  # debootstrap for the base image (deploy/container/make_base.sh)
  docker.io debootstrap
)

# The peer benchmark (bench/run_bench.sh, bench/peer/compare_images.sh) also needs VTK and a
# virtual X server, docs/gallery/make_gallery.sh oiiotool, the verdict set's simulator
# (bench/peer/verdict_set/simulate.py) scipy, and bench/peer/mesh_vs_openvdb.sh OpenVDB (libopenvdb-dev):
# `deploy/setup.sh --bench` adds them.
if [ "${1:-}" = "--bench" ]; then
  PACKAGES+=(python3-vtk9 python3-numpy python3-scipy xvfb xauth openimageio-tools libopenvdb-dev)
fi

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
else
  echo "setup: installing ${missing[*]}"
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The Kubernetes manifests' offline schema check (tests/kubernetes, deploy/kubernetes/validate.cjs)
# uses kubernetes-models and yaml from npm, pinned by deploy/kubernetes/package-lock.json, installed
# into build/npm (git-ignored). Node.js comes with Debian's nodejs; npm separately where it lacks it.
root=$(cd "$(dirname "$0")/.." && pwd)
npm_dir=$root/build/npm
if [ ! -f "$npm_dir/node_modules/kubernetes-models/package.json" ] ||
   ! cmp -s "$root/deploy/kubernetes/package-lock.json" "$npm_dir/package-lock.json"; then
  command -v npm > /dev/null || { $SUDO apt-get update -qq; $SUDO apt-get install -y -qq --no-install-recommends npm; }
  mkdir -p "$npm_dir"
  cp "$root/deploy/kubernetes/package.json" "$root/deploy/kubernetes/package-lock.json" "$npm_dir/"
  echo "setup: npm ci in build/npm (kubernetes-models, yaml)"
  (cd "$npm_dir" && npm ci --no-audit --no-fund --loglevel=error)
fi

# The web viewer's browser tests (tests/web) drive chromium with puppeteer-core from npm, pinned by
# tests/web/package-lock.json, installed into build/npm-web (git-ignored).
web_npm_dir=$root/build/npm-web
if [ ! -f "$web_npm_dir/node_modules/puppeteer-core/package.json" ] ||
   ! cmp -s "$root/tests/web/package-lock.json" "$web_npm_dir/package-lock.json"; then
  mkdir -p "$web_npm_dir"
  cp "$root/tests/web/package.json" "$root/tests/web/package-lock.json" "$web_npm_dir/"
  echo "setup: npm ci in build/npm-web (puppeteer-core)"
  (cd "$web_npm_dir" && npm ci --no-audit --no-fund --loglevel=error)
fi
