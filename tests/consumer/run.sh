#!/usr/bin/env bash
# Installs the build (cmake --install) into a fresh temporary prefix, builds tests/consumer against
# it twice — through the CMake package (find_package(shadowref)) and through pkg-config — runs
# both from the source folder and checks what they print against values the command line gives
# (README.md: the pumpkin scene's stencil counts, the room's pixel history).
#   tests/consumer/run.sh BUILD_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
cd "$(dirname "$0")/../.."
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build" --prefix "$prefix/usr" > /dev/null
test -x "$prefix/usr/bin/shadowref"
test -x "$prefix/usr/bin/shadowref-explore"  # `shadowref explore` hands over to it
test -f "$prefix/usr/include/shadowref/shadowref.h"

# The CMake package.
cmake -S tests/consumer -B "$prefix/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix/usr" > /dev/null
cmake --build "$prefix/build" > /dev/null
# pkg-config (the library's folder for the loader too: the prefix is not a system one).
libdir=$(dirname "$(find "$prefix/usr" -name 'libshadowref.so' | head -1)")
export PKG_CONFIG_PATH=$libdir/pkgconfig
# shellcheck disable=SC2046
c++ -O2 tests/consumer/main.cpp $(pkg-config --cflags --libs shadowref) -Wl,-rpath,"$libdir" -o "$prefix/consumer-pc"

expected='stencil zpass 0 0 0 0 0 0 0 -1 -1 -1 -1 -1
stencil zfail 1 1 1 1 1 1 1 0 0 0 0 0
history draw 41 volume side, object '"'"'room/table/top'"'"' stencil 0 -> 1
history draw 92 lit pass, object '"'"'room/floor'"'"' stencil 1 -> 1
error <command line>:1:13: image.width: expected a whole number, got '"'"'banana'"'"'
animation 1 fps 8 frame 12 same as still 1 frame 0 differs 1'
status=0
for consumer in "$prefix/build/consumer" "$prefix/consumer-pc"; do
  out=$("$consumer")
  got=$(printf '%s\n' "$out" | grep -v '^version ')
  if [ "$got" != "$expected" ]; then
    echo "consumer: $consumer printed" >&2
    printf '%s\n' "$out" >&2
    echo "expected" >&2
    printf '%s\n' "$expected" >&2
    status=1
  fi
  printf '%s\n' "$out" | grep -qx "version $(sed -n 's/^project(shadowref LANGUAGES CXX VERSION \([0-9.]*\)).*/\1/p' CMakeLists.txt)" \
    || { echo "consumer: wrong version line" >&2; status=1; }
done
# The installed CLI loads the image reader installed beside it (lib/.../shadowref/), not the build
# tree's: the dynamic loader names the file it opens.
if [ -f "$build/shadowref_image_reader.so" ]; then
  "$prefix/usr/bin/shadowref" render scenes/minimal.yaml -D image.width=16 -D image.height=12 --quiet -o "$prefix/a.png"
  loaded=$(LD_DEBUG=files "$prefix/usr/bin/shadowref" compare "$prefix/a.png" "$prefix/a.png" 2>&1 > /dev/null |
           grep -o 'file=[^ ]*shadowref_image_reader.so' | head -1)
  case $loaded in
    "file=$prefix/usr/"*) ;;
    *) echo "consumer: the installed CLI loaded '${loaded#file=}', not the installed image reader" >&2; status=1 ;;
  esac
fi
exit $status
