#!/usr/bin/env bash
# Renders every scene in a folder of hostile inputs and checks that each one is refused the way
# bad input must be: exit status 2, the first line of stderr "PATH:LINE:COL: message" (or
# "<command line>:N:COL: message" for a -D), no crash signal, no timeout, no allocation beyond
# the memory limit (1 GB), nothing left in the output folder (neither the image nor a temporary).
# The folder is read when the test runs, so every *.yaml put there is covered; NAME.args next to
# NAME.yaml holds extra arguments (one per line, e.g. "-D" and "camera.near=0"). Every file in
# FOLDER/images/ is compared with itself (`shadowref compare F F`) under the same limits and must
# be refused with compare's bad-input status, 4 (2 is idiff's FAILURE there), and a first line
# naming the file.
#   hostile_scenes.sh SHADOWREF_BINARY FOLDER
set -u
cli=$1
folder=$2
limit_mb=1024
# 20 s of processor time bounds a hang however busy the machine is; the wall-clock limit is there
# for a process that waits without computing.
cpu_seconds=20
wall_seconds=300
# An ASan build reserves terabytes of address space, so `ulimit -v` would stop it at start-up:
# there the sanitizer's own limits bound the memory instead.
asan=false
if ldd "$cli" 2> /dev/null | grep -q libasan; then
  asan=true
  export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}hard_rss_limit_mb=$limit_mb:max_allocation_size_mb=$limit_mb"
fi

failures=0
count=0
for scene in "$folder"/*.yaml "$folder"/images/*; do
  [ -e "$scene" ] || continue
  image=false
  [[ $scene == "$folder"/images/* ]] && image=true
  count=$((count + 1))
  args=()
  if [ -f "${scene%.yaml}.args" ]; then mapfile -t args < "${scene%.yaml}.args"; fi
  out=$(mktemp -d)
  (
    $asan || ulimit -v $((limit_mb * 1024))
    ulimit -t $cpu_seconds
    if $image; then exec timeout -s KILL "$wall_seconds" "$cli" compare "$scene" "$scene"; fi
    exec timeout -s KILL "$wall_seconds" "$cli" render "$scene" "${args[@]}" -o "$out/frame.png" --quiet
  ) > /dev/null 2> "$out.stderr"
  status=$?
  first=$(head -n 1 "$out.stderr")
  problems=()
  expected=2
  $image && expected=4
  [ "$status" -eq "$expected" ] || problems+=("exit status $status, expected $expected$( ((status > 128)) && echo " (signal $((status - 128)))")")
  if $image; then
    [[ $first == *"$scene"* ]] || problems+=("first line of stderr does not name the file")
  else
    [[ $first =~ ^[^:]+:[0-9]+:[0-9]+:\ .+ ]] || problems+=("first line of stderr is not 'PATH:LINE:COL: message'")
  fi
  left=$(ls -A "$out")
  [ -z "$left" ] || problems+=("left in the output folder: $(echo $left)")
  if ((${#problems[@]})); then
    failures=$((failures + 1))
    echo "FAIL $scene ${args[*]}"
    printf '  %s\n' "${problems[@]}"
    sed -n '1,5s/^/  stderr: /p' "$out.stderr"
  else
    echo "ok   $scene: $first"
  fi
  rm -rf "$out" "$out.stderr"
done
echo "$count hostile inputs, $failures failed"
[ "$count" -gt 0 ] && [ "$failures" -eq 0 ]
