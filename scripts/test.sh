#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole test suite through ctest.
#   scripts/test.sh              Release build in build/
#   scripts/test.sh --sanitize   AddressSanitizer + UndefinedBehaviorSanitizer build in build-asan/,
#                                built for any x86-64 (SSE2): the golden frame hashes then show that
#                                both vector widths give the same bytes; the benchmarks are left out,
#                                and so are the tests labelled slow (they run in the Release build)
#                                and the shared library
#   scripts/test.sh ... -L unit  any further arguments go to ctest (README: "Running a part of the tests")
# Under CI (CI=true) warnings are errors.
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir=build
args=()
ctest_args=()
if [ "${1:-}" = "--sanitize" ]; then
  shift
  build_dir=build-asan
  # The installed library (position-independent code, libshadowref.so) is the Release run's to
  # test (install_consumer, labelled slow): the sanitizer build compiles the CLI and the tests only.
  args+=(-DSHADOWREF_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSHADOWREF_X86_64_V3=OFF -DSHADOWREF_BENCH=OFF
         -DSHADOWREF_LIBRARY=OFF)
  ctest_args+=(-LE slow)
fi
if [ "${CI:-}" = "true" ]; then args+=(-DSHADOWREF_WERROR=ON); fi

bash scripts/setup.sh --role test "$build_dir" "${args[@]}"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/tests/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
ctest --test-dir "$build_dir" --output-on-failure -j"$(nproc)" "${ctest_args[@]}" "$@"
