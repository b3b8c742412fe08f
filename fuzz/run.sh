#!/usr/bin/env bash
# Fuzzes the scene loader, the -D overrides and the OBJ/glTF importers with libFuzzer and
# AddressSanitizer. Builds fuzz/scene_loader_fuzz.cpp with clang++-14 directly against
# the library sources (not through the main CMake), seeds the corpus from scenes/ and tests/data/,
# runs for a bounded time and exits non-zero when it finds a crash (the input is kept in
# build-fuzz/artifacts/; turn it into a regression test in tests/scene/loader_fuzz_regressions_test.cpp).
#   fuzz/run.sh [SECONDS=60] [extra libFuzzer flags...]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true

CXX=${CXX:-clang++-14}
out=build-fuzz
mkdir -p "$out/obj" "$out/corpus" "$out/seeds" "$out/artifacts" "$out/work"
flags=(-std=c++20 -g -O1 -fno-omit-frame-pointer -fsanitize=fuzzer-no-link,address -ffp-contract=off
       -DGLM_ENABLE_EXPERIMENTAL -Isrc)

# Compile each library source that changed since its object was built, in parallel.
# The scene library only; it uses raster/ for types alone.
sources=(src/scene/*.cpp fuzz/scene_loader_fuzz.cpp)
export CXX
compile() { "$CXX" "${@:3}" -c "$1" -o "$2"; }
export -f compile
objects=()
stale=()
for src in "${sources[@]}"; do
  obj="$out/obj/$(echo "$src" | tr / _).o"
  objects+=("$obj")
  if [ ! -f "$obj" ] || [ "$src" -nt "$obj" ] || [ -n "$(find src/scene src/raster -name '*.h' -newer "$obj" -print -quit)" ]; then
    stale+=("$src" "$obj")
  fi
done
if ((${#stale[@]})); then
  printf '%s\0' "${stale[@]}" | xargs -0 -n 2 -P "$(nproc)" bash -c 'compile "$0" "$1" '"${flags[*]}"
fi
"$CXX" -fsanitize=fuzzer,address "${objects[@]}" -lyaml-cpp -ltinyobjloader -lpthread -o "$out/scene_loader_fuzz"

# Seeds: the first byte selects the path (see the fuzz target): 0 scene, 0xC0 OBJ, 0xE0 glTF.
seed() { { printf "\\x$1"; cat "$2"; } > "$out/seeds/$(basename "$2").$1"; }
for f in scenes/*.yaml tests/data/scenes/*.yaml; do seed 00 "$f"; done
for f in scenes/meshes/*.obj tests/data/scenes/*.obj tests/data/meshes/*.obj; do [ -f "$f" ] && seed c0 "$f"; done
for f in tests/data/meshes/*.gltf; do [ -f "$f" ] && seed e0 "$f"; done

# Scene seeds name mesh files relative to the working directory: give them scenes/meshes.
rm -rf "$out/work/meshes" && cp -r scenes/meshes "$out/work/meshes"
cd "$out/work"
set +e
ASAN_OPTIONS=detect_leaks=1 ../scene_loader_fuzz -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
  -max_len=65536 -artifact_prefix=../artifacts/ -print_final_stats=1 "$@" ../corpus ../seeds
status=$?
set -e
if [ $status -ne 0 ]; then
  echo "fuzz/run.sh: the fuzzer found a problem (exit $status); inputs in $out/artifacts/" >&2
fi
exit $status
