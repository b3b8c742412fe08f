#!/usr/bin/env bash
# Issue 7's measurement in one command: installs what is missing and builds (scripts/setup.sh),
# then runs bench/vs-mesa, which renders the same frames through OSMesa (softpipe, llvmpipe with
# 1 and 2 threads) and shadowref (1 and 2 threads) in two like-for-like pairs — Mesa's per-vertex
# fixed-function lighting against shadowref with every material Gouraud-shaded, Mesa's per-pixel
# program against shadowref's per-pixel scenes — checks that 1, 2 and 8 threads give identical
# buffers, and times the city against houses and lights. Prints the tables and writes
# bench/results/vs-mesa.csv. Takes a while (softpipe is slow); --quick for fewer runs.
#   scripts/bench-vs-mesa.sh [BUILD_DIR] [--quick] [vs_mesa options: --rounds N --frames N --no-scaling | --series]
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir=build
if (($#)) && [[ $1 != --* ]]; then build_dir=$1; shift; fi
# A build directory configured before bench/ existed needs cmake again to pick it up.
if [ -f "$build_dir/build.ninja" ] && ! grep -q vs_mesa "$build_dir/build.ninja"; then
  cmake "$build_dir" >/dev/null
fi
bash scripts/setup.sh "$build_dir" >/dev/null
cmake --build "$build_dir" --target vs_mesa >/dev/null

args=()
for a in "$@"; do
  if [ "$a" = --quick ]; then args+=(--quick --rounds 3 --frames 3); else args+=("$a"); fi
done
mkdir -p bench/results
{
  echo "commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)$(git diff --quiet -- . ':!bench/results' 2>/dev/null || echo ' (with local changes)')"
  echo "nproc: $(nproc)"
  "$build_dir/bench/vs_mesa" --csv bench/results/vs-mesa.csv "${args[@]}"
} | tee bench/results/vs-mesa.txt
