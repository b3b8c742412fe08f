#!/usr/bin/env bash
# Shows, then (with --write) rewrites, the goldens after an INTENDED change of the output
# (golden/README.md): the golden images of tests/shadow/golden_test.cpp ([golden], shadow volumes:
# golden/<case>.exr), tests/shadow/shadow_map_golden_test.cpp ([golden-sm], shadow maps:
# golden/sm-*.exr) and the frame hashes of tests/shadow/frame_hash_test.cpp
# (golden/frame-hashes.txt, also [golden]); with --write also the golden of docs/python.md's pytest
# example (python/tests/golden/).
#   scripts/update-goldens.sh [--write] [BUILD_DIR]      default BUILD_DIR: build
# Without --write (a dry run) it only runs the golden tests: every golden that would change gets a
# failure report — the golden, this build's frame and their difference, one HTML page per case —
# under BUILD_DIR/golden-report/ (index.html lists them), and nothing in golden/ is touched.
# With --write it shows the same report, then writes the goldens from the reference pipeline
# (SHADOWREF_UPDATE_GOLDENS=1) and runs the golden tests once more to show they pass.
# Review the result before committing: `git diff --stat golden/`.
set -euo pipefail
cd "$(dirname "$0")/.."

write=false
if [ "${1:-}" = "--write" ]; then
  write=true
  shift
fi
build_dir=${1:-build}
bash scripts/setup.sh "$build_dir"
report="$build_dir/golden-report"
rm -rf "$report"
mkdir -p "$report"
export SHADOWREF_GOLDEN_REPORT_DIR="$PWD/$report"
changed=0
for tag in "[golden]" "[golden-sm]"; do
  "$build_dir/tests/shadowref_tests" "$tag" >> "$report/run.log" 2>&1 || changed=1
done
cases=$(find "$report" -mindepth 2 -maxdepth 2 -name index.html | sort)
if [ "$changed" = 0 ]; then
  echo "update-goldens: every golden matches; nothing would change"
else
  echo "update-goldens: these goldens would change (report: $report/index.html):"
  for page in $cases; do echo "  $(basename "$(dirname "$page")"): $page"; done
  [ -n "$cases" ] || { echo "  (no report written: see $report/run.log)"; cat "$report/run.log"; }
fi
if ! $write; then
  [ "$changed" = 0 ] || echo "update-goldens: dry run; scripts/update-goldens.sh --write $build_dir writes them"
  exit 0
fi
for tag in "[golden]" "[golden-sm]"; do
  SHADOWREF_UPDATE_GOLDENS=1 "$build_dir/tests/shadowref_tests" "$tag"
  SHADOWREF_GOLDEN_REPORT_DIR="$PWD/$report/after-write" "$build_dir/tests/shadowref_tests" "$tag"
done
# The golden of the pytest example in docs/python.md (python/tests/golden/), where the Python
# module and pytest are built and found.
if ctest --test-dir "$build_dir" -N -R '^python:pytest$' | grep -q 'python:pytest'; then
  SHADOWREF_UPDATE_GOLDENS=1 ctest --test-dir "$build_dir" -R '^python:pytest$' --output-on-failure
fi
du -ch golden/*.exr | tail -1
