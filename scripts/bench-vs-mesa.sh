#!/usr/bin/env bash
# The comparison with Mesa in one command: installs what is missing and builds (scripts/setup.sh),
# then runs bench/vs-mesa, which renders the same frames through OSMesa (softpipe, llvmpipe with
# 1 and 2 threads) and shadowref (1 and 2 threads) in two like-for-like pairs — Mesa's per-vertex
# fixed-function lighting against shadowref with every material Gouraud-shaded, Mesa's per-pixel
# program against shadowref's per-pixel scenes — checks that 1, 2 and 8 threads give identical
# buffers, and times the city against houses and lights. Prints the tables and writes them to
# OUT_DIR/vs-mesa.txt, every number to OUT_DIR/vs-mesa.csv. OUT_DIR is BUILD_DIR/bench-results
# unless --out names another (paths relative to the repository's root). Nothing is written into
# the source tree: bench/results/ keeps one run, copied there by hand. Takes a while (softpipe is
# slow); --quick for fewer runs.
#   scripts/bench-vs-mesa.sh [BUILD_DIR] [--out OUT_DIR] [--quick] [vs_mesa options: --rounds N --frames N --no-scaling | --series]
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir=build
if (($#)) && [[ $1 != --* ]]; then build_dir=$1; shift; fi
out_dir=$build_dir/bench-results
args=()
while (($#)); do
  case $1 in
    --quick) args+=(--quick --rounds 3 --frames 3) ;;
    --out) [ $# -ge 2 ] || { echo "bench-vs-mesa: --out needs a directory" >&2; exit 2; }; out_dir=$2; shift ;;
    *) args+=("$1") ;;
  esac
  shift
done
# A build directory configured before bench/ existed needs cmake again to pick it up.
if [ -f "$build_dir/build.ninja" ] && ! grep -q vs_mesa "$build_dir/build.ninja"; then
  cmake "$build_dir" >/dev/null
fi
bash scripts/setup.sh "$build_dir" >/dev/null
cmake --build "$build_dir" --target vs_mesa >/dev/null

mkdir -p "$out_dir"
{
  echo "commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)$(git diff --quiet -- . ':!bench/results' 2>/dev/null || echo ' (with local changes)')"
  echo "nproc: $(nproc)"
  "$build_dir/bench/vs_mesa" --csv "$out_dir/vs-mesa.csv" "${args[@]}"
} | tee "$out_dir/vs-mesa.txt"
