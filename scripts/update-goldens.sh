#!/usr/bin/env bash
# Rewrites the golden images in golden/ after an INTENDED change of the shadow-volume output
# (golden/README.md), and the golden of docs/python.md's pytest example. Builds, renders every
# golden case of tests/shadow/golden_test.cpp ([golden], shadow volumes) and
# tests/shadow/shadow_map_golden_test.cpp ([golden-sm], shadow maps: golden/sm-*.exr) and writes
# golden/<case>.exr, then runs the golden tests once more to show they pass.
#   scripts/update-goldens.sh [BUILD_DIR]      default: build
# Review the result before committing: `git diff --stat golden/`, and
# `build/shadowref compare <old>.exr golden/<case>.exr` against a copy of the old file.
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir=${1:-build}
bash scripts/setup.sh "$build_dir"
for tag in "[golden]" "[golden-sm]"; do
  SHADOWREF_UPDATE_GOLDENS=1 "$build_dir/tests/shadowref_tests" "$tag"
  "$build_dir/tests/shadowref_tests" "$tag"
done
# The golden of the pytest example in docs/python.md (python/tests/golden/), where the Python
# module and pytest are built and found.
if ctest --test-dir "$build_dir" -N -R '^python:pytest$' | grep -q 'python:pytest'; then
  SHADOWREF_UPDATE_GOLDENS=1 ctest --test-dir "$build_dir" -R '^python:pytest$' --output-on-failure
fi
du -ch golden/*.exr | tail -1
