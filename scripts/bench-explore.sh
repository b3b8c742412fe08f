#!/usr/bin/env bash
# The explorer's frame rate in a real browser: orbits the camera of each scene in headless Chromium
# for SECONDS and prints frames shown per second, the server's time per frame, the latency from
# input to image, the CPU time per frame of the server and the browser and the frame rate that
# allows on two idle cores (tests/browser/explore_bench.mjs; docs/performance.md keeps a run).
# Needs scripts/setup.sh --role test (Chromium, tests/browser/node_modules) and a built CLI.
#   scripts/bench-explore.sh [BUILD_DIR] [SECONDS] [SCENE...]   (defaults: build, 10, room, pumpkins and city)
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${1:-build}
seconds=${2:-10}
shift $(( $# > 2 ? 2 : $# )) || true
[ -x "$build_dir/shadowref" ] || { echo "bench-explore: no $build_dir/shadowref; build it first" >&2; exit 2; }
[ -d tests/browser/node_modules ] || { echo "bench-explore: run scripts/setup.sh --role test (npm ci in tests/browser)" >&2; exit 2; }
echo "$(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg); 800x640"
exec node tests/browser/explore_bench.mjs "$build_dir/shadowref" "$seconds" "$@"
