#!/usr/bin/env bash
# Set-up shared by the README's two commands: install what is missing
# (Debian 12, as root; quiet and idempotent), then configure and build.
#   BUILD_DIR   build directory (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  # ParaView 5.11 and its bundled VTK 9.2, with Python
  paraview-dev paraview python3-paraview
  # what find_package(ParaView) needs but paraview-dev does not pull in
  libopenmpi-dev libhdf5-mpi-dev libutfcpp-dev libglew-dev qtbase5-dev libqt5svg5-dev
  qttools5-dev libqt5opengl5-dev libxml2-dev libboost-dev libtheora-dev libavformat-dev
  libavcodec-dev libavutil-dev libswscale-dev libgl2ps-dev libpng-dev libnetcdf-dev
  libgdal-dev libx11-dev libpython3-dev libexpat1-dev liblzma-dev liblz4-dev
  libdouble-conversion-dev libjpeg-dev libtiff-dev libfreetype-dev zlib1g-dev
  # the GL compute layer: headers, GLM, and headless OpenGL at run time
  # (EGL and OSMesa on Mesa's llvmpipe when there is no GPU)
  libgl-dev libegl-dev libglm-dev libosmesa6-dev libegl1 libegl-mesa0 libgl1-mesa-dri libosmesa6
  # an X server for the tests that run inside an ordinary VTK window, and
  # real pointer events for the GUI drag test
  xvfb xdotool
  # the GUI tests that read ParaView's Properties panel (its Qt widgets)
  python3-pyqt5
  # image regression tests: OpenImageIO's library (comparison) and idiff
  libopenimageio-dev openimageio-tools
  # the command line's option parser (header-only)
  libcli11-dev
  # toolchain; clang for the libFuzzer targets of the file-header checks
  cmake g++ ninja-build clang libclang-rt-14-dev
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${#missing[@]} missing package(s): ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

build="${BUILD_DIR:-build}"
if [ ! -f "$build/build.ninja" ]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >"$build.configure.log" 2>&1 \
    || { cat "$build.configure.log"; exit 1; }
fi
cmake --build "$build" -- -j"$(nproc)" >"$build.build.log" 2>&1 || { tail -50 "$build.build.log"; exit 1; }
