#!/usr/bin/env bash
# Installs what is missing, builds, and renders the built-in default scene (the room) to
# out/default.png and out/default.exr.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh build
./build/shadowref render -o out/default.png -o out/default.exr "$@"
