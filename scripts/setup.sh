#!/usr/bin/env bash
# Installs every Debian package shadowref needs (only what is missing) and builds it.
# Idempotent: a second run does nothing but an incremental build.
#   scripts/setup.sh [BUILD_DIR] [extra cmake args...]
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config ccache
  libglm-dev libpng-dev libopenexr-dev nettle-dev libopenimageio-dev openimageio-tools
  catch2 libyaml-cpp-dev libtinygltf-dev nlohmann-json3-dev libcli11-dev
  libosmesa6-dev clang libclang-rt-14-dev gnuplot-nox
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

build_dir=${1:-build}
shift || true
# ccache keeps the objects of earlier builds, of this checkout or any other: paths are taken
# relative to the checkout (CCACHE_BASEDIR) and the working directory is not hashed, so a fresh
# clone in another folder rebuilds from the cache. The compiler and its flags still decide every
# byte; the cache only skips recompiling what it has already seen.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}
export CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-true}
if [ ! -f "$build_dir/build.ninja" ] || [ $# -gt 0 ]; then
  cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER_LAUNCHER=ccache "$@" >/dev/null 2>"$build_dir.cmake.log" \
    || { cat "$build_dir.cmake.log" >&2; exit 1; }
fi
cmake --build "$build_dir"
