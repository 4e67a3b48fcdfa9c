#!/usr/bin/env bash
# Installs every Debian 12 package fluidcast needs to build, test and run the demo.
# Idempotent: installs only what is missing. Needs root (uses sudo when not root).
set -euo pipefail

PACKAGES=(
  # toolchain
  build-essential cmake pkg-config git
  # GL through EGL with no display, software rasterizer (llvmpipe) where there is no GPU
  libepoxy-dev libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  # image encoding
  libopenimageio-dev
  # compressed frame uploads
  libzstd-dev
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
  # the Python binding (python/fluidcast) and its tests under Debian's python3
  python3-numpy python3-pytest
  # "srv:" addresses: a real DNS server (dnsmasq, its binary alone) serves SRV records in tests/srv
  dnsmasq-base
  # deploy/slurm's batch scripts run on a one-host Slurm cluster in the tests (tests/slurm,
  # deploy/slurm/test-cluster.sh): its daemons, munge, and ss to pick free ports
  slurm-wlm munge iproute2
)

# The peer benchmark (bench/run_bench.sh, bench/peer/compare_images.sh) also needs VTK and a
# virtual X server, and docs/gallery/make_gallery.sh oiiotool:
# `deploy/setup.sh --bench` adds them.
if [ "${1:-}" = "--bench" ]; then
  PACKAGES+=(python3-vtk9 python3-numpy xvfb xauth openimageio-tools)
fi

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
