#!/usr/bin/env bash
# Rewrites the golden images in golden/ after an INTENDED change of the shadow-volume output
# (golden/README.md). Builds, renders every golden case of tests/shadow/golden_test.cpp
# ([golden], shadow volumes) and tests/shadow/shadow_map_golden_test.cpp ([golden-sm], shadow maps:
# golden/sm-*.exr) and writes golden/<case>.exr, then runs the golden tests once more to show
# they pass.
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
du -ch golden/*.exr | tail -1
