#!/usr/bin/env bash
# Installs the Debian packages a role needs (only what is missing) and builds what it uses.
# Idempotent: a second run does nothing but an incremental build.
#   scripts/setup.sh [--role render|test|bench] [BUILD_DIR] [extra cmake args...]
# Roles, each including the one before:
#   render  the compiler, CMake and the libraries the CLI links (glm, yaml-cpp, tinygltf, CLI11,
#           libpng, OpenEXR, nettle); builds only the CLI (scripts/render-default.sh)
#   test    + OpenImageIO (the image-reading module of `compare`, and the tests' reader), Catch2,
#           OSMesa (the conformance tests), clang and its runtimes (fuzzing), GNU parallel (the sweep
#           scale-out test); builds everything
#           (scripts/test.sh)
#   bench   + gnuplot, hyperfine and GNU time, for the benchmark scripts (scripts/bench-*.sh)
# Without --role: bench, i.e. everything.
set -euo pipefail
cd "$(dirname "$0")/.."

role=bench
if [ "${1:-}" = "--role" ]; then
  role=${2:-}
  shift 2 || { echo "setup: --role needs render, test or bench" >&2; exit 2; }
fi
render_packages=(
  build-essential cmake ninja-build pkg-config ccache
  libglm-dev libyaml-cpp-dev libtinygltf-dev nlohmann-json3-dev libcli11-dev
  libpng-dev libopenexr-dev nettle-dev
)
test_packages=(libopenimageio-dev openimageio-tools catch2 libosmesa6-dev clang libclang-rt-14-dev parallel)
bench_packages=(gnuplot-nox hyperfine time)
case $role in
  render) packages=("${render_packages[@]}") ;;
  test) packages=("${render_packages[@]}" "${test_packages[@]}") ;;
  bench) packages=("${render_packages[@]}" "${test_packages[@]}" "${bench_packages[@]}") ;;
  *) echo "setup: unknown role '$role' (render, test or bench)" >&2; exit 2 ;;
esac
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
# What the role builds. A render-only build leaves out tests and benchmarks (and their
# dependencies); a test or bench run turns them on in a build folder a render made.
case $role in
  render) role_args=(-DSHADOWREF_TESTS=OFF -DSHADOWREF_BENCH=OFF); targets=(--target shadowref) ;;
  test | bench) role_args=(-DSHADOWREF_TESTS=ON); targets=() ;;
esac
configure=false
if [ ! -f "$build_dir/build.ninja" ] || [ $# -gt 0 ]; then
  configure=true
elif [ "$role" != render ] && ! grep -q '^SHADOWREF_TESTS:BOOL=ON$' "$build_dir/CMakeCache.txt"; then
  configure=true
fi
[ "$role" = bench ] && ! grep -q '^SHADOWREF_BENCH:BOOL=ON$' "$build_dir/CMakeCache.txt" 2>/dev/null && configure=true
[ "$role" = bench ] && role_args+=(-DSHADOWREF_BENCH=ON)
# An existing build folder keeps its tests when a render builds in it.
[ "$role" = render ] && [ -f "$build_dir/CMakeCache.txt" ] && role_args=()
# ccache keeps the objects of earlier builds, of this checkout or any other: paths are taken
# relative to the checkout (CCACHE_BASEDIR) and the working directory is not hashed, so a fresh
# clone in another folder rebuilds from the cache. The compiler and its flags still decide every
# byte; the cache only skips recompiling what it has already seen.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}
export CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-true}
if $configure; then
  mkdir -p "$build_dir"
  cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER_LAUNCHER=ccache \
        "${role_args[@]}" "$@" >/dev/null 2>"$build_dir.cmake.log" \
    || { cat "$build_dir.cmake.log" >&2; exit 1; }
fi
cmake --build "$build_dir" "${targets[@]}"
