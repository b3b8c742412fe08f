#!/usr/bin/env bash
# Fuzzes everything a user feeds shadowref with libFuzzer, AddressSanitizer and
# UndefinedBehaviorSanitizer (float-cast-overflow included; every finding aborts):
#   scene_loader   a scene file, with lines "#D key=value" as -D overrides
#   obj_import     an OBJ file and the material library its mtllib names
#   gltf_import    a .gltf or .glb file and an external .bin buffer
#   cli            an argument vector for the shadowref command line (render, check, info, compare)
#   image_compare  PNG / EXR / other bytes read by `shadowref compare`
#   render_values  the numbers of a fixed valid scene, rendered at 16x16 with every shadow method
#   differential   a command stream, rendered by the reference pipeline and the fast executor at
#                  one and three threads, stopping at the first byte that differs
#   trace          a trace file (render --capture), parsed, replayed on the reference and compared
# Each target is one file fuzz/<target>_fuzz.cpp, linked against static libraries built here with
# clang++-14 straight from src/ (not through the main CMake): objects are rebuilt only when their
# source or a header is newer, shared by all targets, two compiles at a time (FUZZ_JOBS).
# Seeds: fuzz/corpus/<target>/ (small, minimised, in the repository), the scenes and meshes in
# scenes/ and tests/data/, and large inputs (50 KB and more) generated here. Each target runs for
# SECONDS in build-fuzz/<target>/; the run exits non-zero when any target found a crash, a
# sanitizer report, a timeout or an allocation beyond the memory limit, and keeps the input in
# build-fuzz/artifacts/<target>/. Turn every such input into a regression test.
#   fuzz/run.sh [SECONDS=60] [TARGET...] [-libFuzzer-flag...]
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
seconds=${1:-60}
shift || true
all_targets=(scene_loader obj_import gltf_import cli image_compare render_values differential trace)
targets=()
fuzz_flags=()
for arg in "$@"; do
  if [[ $arg == -* ]]; then fuzz_flags+=("$arg"); else targets+=("$arg"); fi
done
((${#targets[@]})) || targets=("${all_targets[@]}")

CXX=${CXX:-clang++-14}
launcher=""
command -v ccache > /dev/null && launcher=ccache
# Objects compiled in any checkout on this machine are reused (see scripts/setup.sh).
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$root} CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-true}
out=$root/build-fuzz
mkdir -p "$out/obj" "$out/lib" "$out/gen"
# The build facts the CLI's --version reports, which CMake generates for the real build.
printf '#pragma once\n#define SHADOWREF_VERSION "fuzz"\n#define SHADOWREF_ISA_LEVEL "fuzz"\n#define SHADOWREF_COMPILER "clang++-14"\n#define SHADOWREF_BUILD_TYPE "fuzz"\n' > "$out/gen/build_info.h.new"
printf '#pragma once\n#define SHADOWREF_REVISION "fuzz"\n' > "$out/gen/build_revision.h.new"
for h in build_info.h build_revision.h; do
  if cmp -s "$out/gen/$h.new" "$out/gen/$h"; then rm "$out/gen/$h.new"; else mv "$out/gen/$h.new" "$out/gen/$h"; fi
done
sanitizers=fuzzer-no-link,address,undefined,float-cast-overflow
flags=(-std=c++20 -g -O1 -fno-omit-frame-pointer -fsanitize=$sanitizers -fno-sanitize-recover=all
       -ffp-contract=off -fno-fast-math -Wno-psabi -DGLM_ENABLE_EXPERIMENTAL -Isrc -Isupport -I. -I"$out/gen"
       $(pkg-config --cflags OpenEXR)
       # The image reader (OpenImageIO) linked in, not loaded as a module: it is fuzzed too.
       -DSHADOWREF_IMAGE_READER_LINKED)

# The libraries (folders of src/) each target needs, in link order.
libs_of() {
  case $1 in
    scene_loader | obj_import | gltf_import) echo scene pipeline ;;
    render_values) echo shadow scene pipeline ;;
    image_compare) echo image pipeline ;;
    differential) echo pipeline ;;
    trace) echo trace shadow scene image pipeline ;;
    cli) echo cli explore sweep trace oracle views shadow scene image pipeline ;;
    *) echo "fuzz/run.sh: unknown target '$1' (targets: ${all_targets[*]})" >&2; return 1 ;;
  esac
}
declare -A needed=()
for t in "${targets[@]}"; do
  for l in $(libs_of "$t"); do needed[$l]=1; done
done

# Compile every stale object (source or any header newer than the object) in parallel.
stale=()
consider() {  # source object
  if [ ! -f "$2" ] || [ "$1" -nt "$2" ] || [ -n "$(find src -name '*.h' -newer "$2" -print -quit)" ]; then
    stale+=("$1" "$2")
  fi
}
# A library's sources: its folder of src/, for the pipeline the three folders CMake's
# shadowref_pipeline is made of, for image also the reader module's folder.
sources_of() {
  case $1 in
    pipeline) echo src/gl/*.cpp src/exec/*.cpp src/memory/*.cpp ;;
    image) echo src/image/*.cpp src/image/oiio/*.cpp ;;
    explore) echo src/explore/*.cpp "$out/gen/explore_page.cpp" ;;
    *) echo src/"$1"/*.cpp ;;
  esac
}
# The explorer's page, compiled in as the CMake build does it (written only when it changes).
if [ -n "${needed[explore]:-}" ]; then
  mkdir -p "$out/gen"
  pages=(src/explore/page/*)
  cmake "-DFILES=$(IFS=';'; echo "${pages[*]}")" -DOUTPUT="$out/gen/explore_page.cpp" -P cmake/embed_files.cmake
fi
# Not the programs' own files: main, and the explore hand-over, whose stand-in server would take
# the real one's place.
for l in "${!needed[@]}"; do
  for src in $(sources_of "$l"); do
    case $src in src/cli/main.cpp | src/cli/explore_handover.cpp) continue ;; esac
    consider "$src" "$out/obj/$(echo "$src" | tr / _).o"
  done
done
for t in "${targets[@]}"; do consider "fuzz/${t}_fuzz.cpp" "$out/obj/fuzz_${t}_fuzz.o"; done
export CXX launcher
compile() { $launcher "$CXX" "${@:3}" -c "$1" -o "$2"; }
export -f compile
if ((${#stale[@]})); then
  echo "fuzz/run.sh: compiling $((${#stale[@]} / 2)) sources" >&2
  printf '%s\0' "${stale[@]}" | xargs -0 -n 2 -P "${FUZZ_JOBS:-2}" bash -c 'compile "$0" "$1" '"${flags[*]}"
fi
for l in "${!needed[@]}"; do
  objects=()
  for src in $(sources_of "$l"); do
    case $src in src/cli/main.cpp | src/cli/explore_handover.cpp) ;; *) objects+=("$out/obj/$(echo "$src" | tr / _).o") ;; esac
  done
  lib=$out/lib/lib$l.a
  if [ ! -f "$lib" ] || [ -n "$(find "${objects[@]}" -newer "$lib" -print -quit)" ]; then
    rm -f "$lib" && ar rcs "$lib" "${objects[@]}"
  fi
done
for t in "${targets[@]}"; do
  libs=()
  for l in $(libs_of "$t"); do libs+=("$out/lib/lib$l.a"); done
  extra=(-lyaml-cpp)
  case $t in image_compare | cli | trace) extra+=($(pkg-config --libs OpenImageIO libpng OpenEXR nettle)) ;; esac
  [ "$t" = cli ] && extra+=($(pkg-config --libs cpp-httplib))
  "$CXX" -fsanitize=fuzzer,$sanitizers "$out/obj/fuzz_${t}_fuzz.o" "${libs[@]}" "${extra[@]}" -lpthread -o "$out/${t}_fuzz"
done

# Seeds: the committed corpus, the repository's own inputs, and generated large ones.
seed_dir() { rm -rf "$out/seeds/$1" && mkdir -p "$out/seeds/$1" && cp -r fuzz/corpus/"$1"/. "$out/seeds/$1"/ 2> /dev/null || true; }
seeds_scene_loader() {
  cp scenes/*.yaml tests/data/scenes/*.yaml "$out/seeds/scene_loader/"
  # A long scene: a thousand nodes with transforms (~70 KB).
  { cat scenes/minimal.yaml
    for i in $(seq 1 1000); do
      echo "  - {name: n$i, mesh: box, material: red, translate: [$i, 0.5, -$i], scale: [0.5, 1, 0.5]}"
    done; } > "$out/seeds/scene_loader/big_nodes.yaml"
}
seeds_obj_import() {
  for f in scenes/meshes/*.obj tests/data/meshes/*.obj tests/data/scenes/*.obj; do cp "$f" "$out/seeds/obj_import/"; done
  # A 36x36 grid (~90 KB) with a material library after the "#---mtl" line.
  python3 - "$out/seeds/obj_import/big_grid.obj" << 'EOF'
import sys
n = 36
lines = ["mtllib side.mtl", "usemtl a"]
lines += [f"v {x * 0.1:.4f} {((x * 7 + y * 13) % 17) * 0.01:.4f} {y * 0.1:.4f}" for y in range(n) for x in range(n)]
lines += [f"vn 0 1 0"]
for y in range(n - 1):
    for x in range(n - 1):
        a = y * n + x + 1
        lines.append(f"f {a}//1 {a + n}//1 {a + 1}//1")
        lines.append(f"f {a + 1}//1 {a + n}//1 {a + n + 1}//1")
lines += ["#---mtl", "newmtl a", "Kd 0.8 0.2 0.1", "Ns 20"]
open(sys.argv[1], "w").write("\n".join(lines) + "\n")
EOF
}
seeds_gltf_import() {
  for f in tests/data/meshes/*.gltf; do { printf 'j'; cat "$f"; } > "$out/seeds/gltf_import/$(basename "$f")"; done
  # A large .glb (~100 KB of vertices and indices) and the same mesh as .gltf with an external .bin.
  python3 - "$out/seeds/gltf_import" << 'EOF'
import json, struct, sys
n = 48
pos = b"".join(struct.pack("<3f", x * 0.1, 0.0, y * 0.1) for y in range(n) for x in range(n))
idx = b"".join(struct.pack("<6I", a, a + n, a + 1, a + 1, a + n, a + n + 1)
               for a in (y * n + x for y in range(n - 1) for x in range(n - 1)))
data = pos + idx
def doc(uri):
    buf = {"byteLength": len(data)}
    if uri: buf["uri"] = uri
    return {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
            "buffers": [buf],
            "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                            {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": n * n, "type": "VEC3",
                           "min": [0, 0, 0], "max": [(n - 1) * 0.1, 0, (n - 1) * 0.1]},
                          {"bufferView": 1, "componentType": 5125, "count": len(idx) // 4, "type": "SCALAR"}]}
sep = b"\n#---bin\n"
open(sys.argv[1] + "/big_external.gltf", "wb").write(b"j" + json.dumps(doc("side.bin")).encode() + sep + data)
js = json.dumps(doc(None)).encode()
js += b" " * (-len(js) % 4)
glb = struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(js) + 8 + len(data))
glb += struct.pack("<I4s", len(js), b"JSON") + js + struct.pack("<I4s", len(data), b"BIN\0") + data
open(sys.argv[1] + "/big.glb", "wb").write(b"b" + glb)
EOF
}
seeds_cli() {
  # A long argument vector (~60 KB): the minimal scene with 2500 -D overrides.
  { printf 'render\nminimal.yaml\n-o\nx.png\n'
    for i in $(seq 1 2500); do printf -- '-D\ncamera.near=0.%05d\n' "$i"; done; } > "$out/seeds/cli/big_overrides"
}
seeds_image_compare() {
  # A 160x160 noisy PNG (~77 KB, does not compress) and a 64x64 EXR with a Z channel (~85 KB).
  python3 - "$out/seeds/image_compare/big.png" << 'EOF'
import random, struct, sys, zlib
w = h = 160
random.seed(1)
raw = b"".join(b"\0" + bytes(random.randrange(256) for _ in range(3 * w)) for _ in range(h))
def chunk(kind, body):
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
png += chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")
open(sys.argv[1], "wb").write(b"p" + png)
EOF
  oiiotool --pattern noise 64x64 4 --ch R,G,B,A,Z=1 -d float -o "$out/big.exr" > /dev/null 2>&1 &&
    { printf 'e'; cat "$out/big.exr"; } > "$out/seeds/image_compare/big.exr" || true
}
seeds_render_values() {
  # Sixty-odd numbers of a thousand digits each (~65 KB).
  python3 -c "print('\n'.join('0.' + '0' * 990 + '123456789' if i % 2 else '1' + '0' * 999 for i in range(64)))" \
    > "$out/seeds/render_values/long_digits"
}
seeds_differential() {
  # Random command streams of a few hundred bytes (the seeded generator keeps them the same).
  python3 -c "
import random, sys
r = random.Random(7)
for i in range(16):
    open(sys.argv[1] + '/random%02d' % i, 'wb').write(bytes(r.randrange(256) for _ in range(r.randrange(64, 1024))))
" "$out/seeds/differential"
}

seeds_trace() {
  # A larger trace (~100 KB): the minimal scene's z-fail frame at 24x18.
  if [ -x build/shadowref ]; then
    sed -e 's/width: 640/width: 24/' -e 's/height: 480/height: 18/' scenes/minimal.yaml > "$out/minimal-24.yaml"
    build/shadowref render "$out/minimal-24.yaml" --method zfail -o "$out/minimal-24.png" \
      --capture "$out/seeds/trace/minimal-zfail-24x18.srtrace" --quiet || true
  fi
}

# The scratch folder each target writes its side files into, and a few files the command line
# fuzzer names by name (a 16x16 scene, two small images).
prepare_work() {
  rm -rf "$out/$1" && mkdir -p "$out/$1/work" "$out/corpus/$1" "$out/artifacts/$1"
  case $1 in
    scene_loader) cp -r scenes/meshes "$out/$1/work/meshes" ;;
    cli)
      sed -e 's/width: 640/width: 16/' -e 's/height: 480/height: 16/' scenes/minimal.yaml > "$out/$1/work/minimal.yaml"
      cp tests/data/scenes/bad_syntax.yaml "$out/$1/work/bad.yaml"
      oiiotool --pattern constant:color=0.5,0.25,1 8x8 3 -d uint8 -o "$out/$1/work/a.png" > /dev/null
      oiiotool --pattern noise 8x8 4 -d float -o "$out/$1/work/b.exr" > /dev/null ;;
  esac
}

status=0
for t in "${targets[@]}"; do
  seed_dir "$t"
  "seeds_$t"
  prepare_work "$t"
  dict=()
  [ -f "fuzz/$t.dict" ] && dict=(-dict="$root/fuzz/$t.dict")
  echo "fuzz/run.sh: $t for $seconds s" >&2
  set +e
  (cd "$out/$t/work" &&
    ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    LSAN_OPTIONS=suppressions="$root/fuzz/lsan.supp":print_suppressions=0 \
      "$out/${t}_fuzz" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 \
      -max_len=131072 -artifact_prefix="$out/artifacts/$t/" -print_final_stats=1 "${dict[@]}" \
      "${fuzz_flags[@]}" "$out/corpus/$t" "$out/seeds/$t") 2>&1 | tee "$out/$t/log" |
    grep -E '^(#[0-9]+[[:space:]]+(INITED|DONE)|stat::|==[0-9]+==ERROR|SUMMARY|.*runtime error|artifact_prefix|Test unit written)' >&2
  result=${PIPESTATUS[0]}
  set -e
  if [ "$result" -ne 0 ]; then
    echo "fuzz/run.sh: $t found a problem (exit $result): see $out/$t/log, inputs in $out/artifacts/$t/" >&2
    status=1
  fi
done
exit $status
