#!/usr/bin/env bash
# Rewrites the golden images in golden/ after an INTENDED change of the shadow-volume output
# (golden/README.md). Builds, renders every golden case of tests/shadow/golden_test.cpp and
# writes golden/<case>.exr, then runs the golden tests once more to show they pass.
#   scripts/update-goldens.sh [BUILD_DIR]      default: build
# Review the result before committing: `git diff --stat golden/`, and
# `build/shadowref compare <old>.exr golden/<case>.exr` against a copy of the old file.
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir=${1:-build}
bash scripts/setup.sh "$build_dir"
SHADOWREF_UPDATE_GOLDENS=1 "$build_dir/tests/shadowref_tests" "[golden]"
"$build_dir/tests/shadowref_tests" "[golden]"
du -ch golden/*.exr | tail -1
