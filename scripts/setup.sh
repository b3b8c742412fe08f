#!/usr/bin/env bash
# Installs the Debian packages a role needs (only what is missing) and builds what it uses.
# Idempotent: a second run does nothing but an incremental build.
#   scripts/setup.sh [--role render|test|bench] [BUILD_DIR] [extra cmake args...]
# Roles, each including the one before:
#   render  the compiler, CMake and the libraries the CLI links (glm, yaml-cpp, tinygltf, CLI11,
#           libpng, OpenEXR, nettle, cpp-httplib); builds the CLI only: shadowref and the
#           shadowref-explore it hands `explore` to (scripts/render-default.sh)
#   test    + pybind11, NumPy and Python's headers (the Python module),
#           OpenImageIO (the image-reading module of `compare`, and the tests' reader), Catch2,
#           OSMesa (the conformance tests), clang and its runtimes (fuzzing), pytest, nbclient,
#           ipykernel and matplotlib (the Python tests and the notebook), Chromium and
#           tests/browser's npm packages (the explorer's browser test), ffmpeg (run, not linked,
#           by `render --frames --gif/--mp4`; the tests decode its movies with ffprobe), GNU
#           parallel (the sweep scale-out test); builds everything (scripts/test.sh)
# Where the Python module was built, the python3 on the PATH is pointed at it (a .pth file in its
# site folder naming BUILD_DIR/python), so that `python3 -c "import shadowref"` works from then on
# and always loads the latest build.
#   bench   + gnuplot, hyperfine and GNU time, for the benchmark scripts (scripts/bench-*.sh)
# Without --role: bench, i.e. everything.
set -euo pipefail
cd "$(dirname "$0")/.."

role=bench
if [ "${1:-}" = "--role" ]; then
  role=${2:-}
  shift 2 || { echo "setup: --role needs render, test or bench" >&2; exit 2; }
fi
# The render role's are what a fresh machine downloads before its first picture: g++ rather than
# build-essential (make, dpkg-dev and Perl, which a Ninja build never runs), no Python.
render_packages=(
  g++ cmake ninja-build pkg-config ccache
  libglm-dev libyaml-cpp-dev libtinygltf-dev nlohmann-json3-dev libcli11-dev
  libpng-dev libopenexr-dev nettle-dev libcpp-httplib-dev
)
test_packages=(python3-dev pybind11-dev python3-numpy
               libopenimageio-dev openimageio-tools catch2 libosmesa6-dev libegl-dev libegl-mesa0 clang libclang-rt-14-dev chromium ffmpeg parallel
               python3-pytest python3-nbclient python3-nbformat python3-ipykernel python3-matplotlib)
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

# The browser test's driver (tests/browser/: puppeteer-core, pinned by its package-lock.json) for
# the Chromium above; npm ci again only when the lock file is newer than what it installed.
if [ "$role" != render ]; then
  lock=tests/browser/package-lock.json
  if ! command -v npm >/dev/null; then
    echo "setup: installing npm" >&2
    SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends nodejs npm >/dev/null
  fi
  if [ ! -f tests/browser/node_modules/.package-lock.json ] || [ $lock -nt tests/browser/node_modules/.package-lock.json ]; then
    (cd tests/browser && npm ci --no-audit --no-fund --loglevel=error)
  fi
fi

build_dir=${1:-build}
shift || true
# What the role builds. A render-only build leaves out tests and benchmarks (and their
# dependencies); a test or bench run turns them on in a build folder a render made (the
# benchmarks too: bench/tests is part of the suite). Arguments after BUILD_DIR come later on
# cmake's command line and win (scripts/test.sh --sanitize leaves the benchmarks out). Every role
# builds from scratch once: the libraries are compiled as unity builds (SHADOWREF_UNITY_BUILD, a
# few files per compiler run), which the folder keeps (-DSHADOWREF_UNITY_BUILD=OFF for editing);
# the test role building them so is what proves every batch compiles.
case $role in
  render) role_args=(-DSHADOWREF_TESTS=OFF -DSHADOWREF_BENCH=OFF -DSHADOWREF_UNITY_BUILD=ON); targets=(--target shadowref) ;;
  test | bench) role_args=(-DSHADOWREF_TESTS=ON -DSHADOWREF_BENCH=ON -DSHADOWREF_UNITY_BUILD=ON); targets=() ;;
esac
configure=false
if [ ! -f "$build_dir/build.ninja" ] || [ $# -gt 0 ]; then
  configure=true
elif [ "$role" != render ] && ! { grep -q '^SHADOWREF_TESTS:BOOL=ON$' "$build_dir/CMakeCache.txt" &&
                                  grep -q '^SHADOWREF_BENCH:BOOL=ON$' "$build_dir/CMakeCache.txt"; }; then
  configure=true
fi
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

# `python3 -c "import shadowref"`: a .pth file in the site folder of the python3 on the PATH names
# the build's package folder (as `pip install -e` would), and another in the site folder of the
# interpreter the module was built for (CMakeCache: Python3_EXECUTABLE, the one with NumPy; also
# Debian's Jupyter kernel) when that is not the same. When `python3` is another interpreter of the
# same version (pyenv, a venv), its .pth names the built-for one's package folders too, for NumPy.
package_dir=$PWD/$build_dir/python
write_pth() {  # PYTHON LINE...: writes the lines to PYTHON's shadowref.pth
  local site_dir sudo=""
  site_dir=$("$1" -c 'import site; print(site.getsitepackages()[0])')
  shift
  [ "$(id -u)" -ne 0 ] && [ ! -w "$(dirname "$site_dir")" ] && sudo="sudo"
  $sudo mkdir -p "$site_dir"
  printf '%s\n' "$@" | $sudo tee "$site_dir/shadowref.pth" > /dev/null
}
if [ -f "$package_dir/shadowref/__init__.py" ]; then
  built_for=$(sed -n 's/^Python3_EXECUTABLE:[A-Z]*=//p' "$build_dir/CMakeCache.txt")
  [ -n "$built_for" ] && write_pth "$built_for" "$package_dir"
  on_path=$(command -v python3 || true)
  if [ -n "$on_path" ] && [ "$(realpath "$on_path")" != "$(realpath "${built_for:-/nonexistent}" 2>/dev/null)" ]; then
    lines=("$package_dir")
    version='import sys; print(sys.version_info[:2])'
    if [ -n "$built_for" ] && [ "$(python3 -c "$version")" = "$("$built_for" -c "$version")" ]; then
      while IFS= read -r line; do lines+=("$line"); done < <("$built_for" -c \
        'import site; print("\n".join(p for p in site.getsitepackages() if "-packages" in p))')
    fi
    write_pth python3 "${lines[@]}"
  fi
fi
