#!/usr/bin/env bash
# Installs what rendering needs (scripts/setup.sh --role render: no test or benchmark packages),
# builds the CLI only, and renders the built-in default scene (the room) to out/default.png and
# out/default.exr.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --role render build
./build/shadowref render -o out/default.png -o out/default.exr "$@"
