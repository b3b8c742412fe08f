#!/usr/bin/env bash
# The documents' scenes captured and replayed on Mesa as a user does it: `shadowref render
# --capture` of the room and the pumpkins ([Kuhn 2016, Fig. 5.1, 5.2]) with z-fail and shadow maps
# at 320x240 (maps of 512), then `shadowref replay --on osmesa:llvmpipe|osmesa:softpipe`, each
# report turned into rows of the table in docs/conformance.md (between the conformance-scenes
# markers). The table is nothing but the replay reports: --check compares it with a fresh run
# and fails when they differ (ctest runs that).
#   scripts/conformance-scenes.sh [--check] [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/doc-section.sh
check=false
if [ "${1:-}" = "--check" ]; then
  check=true
  shift
fi
build_dir=${1:-build}
shadowref="$build_dir/shadowref"
[ -x "$shadowref" ] || { echo "conformance-scenes: no $shadowref (build it first)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# One replay report (stdin) as table rows: frame | target | framebuffer | buffer | pixels | near an
# edge | differing on an edge / on a near-plane cut / elsewhere | largest off the edges / allowed |
# verdict.
rows_of() {
  awk -v frame="$1" -v target="$2" '
    /^framebuffer / { fb = $2; kind = ($3 == "(the" ? "frame" : "shadow map"); next }
    /^  [a-z]+ +[0-9]+ pixels,/ {
      on = ""; near = "0"; other = ""; off = ""; allowed = ""
      for (i = 1; i <= NF; ++i) {
        if ($i == "on" && $(i + 1) == "an" && $(i + 2) == "edge,") on = $(i - 1)
        if ($i == "on" && $(i + 1) == "a" && $(i + 2) == "near-plane") near = $(i - 1)
        if ($i == "elsewhere;") other = $(i - 1)
        if ($i == "(off" && $(i + 1) == "the" && $(i + 2) == "edges") { off = $(i + 3); sub(/,$/, "", off) }
        if ($i == "allowed") { allowed = $(i + 1); sub(/\):$/, "", allowed) }
      }
      verdict = $0
      sub(/^.*\): /, "", verdict)
      printf "| %s | %s | %s (%s) | %s | %s | %s | %s / %s / %s | %s / %s | %s |\n", frame, target, fb, kind, $1, $2, $4, on, near, other, off, allowed, verdict
    }'
}

table="$work/table.md"
{
  echo "| frame | replayed on | framebuffer | buffer | pixels | near an edge | differing: on an edge / near-plane cut / elsewhere | largest difference off the edges / allowed | verdict |"
  echo "|---|---|---|---|---|---|---|---|---|"
  for scene in room pumpkins; do
    for method in zfail shadowmap; do
      trace="$work/$scene-$method.srtrace"
      "$shadowref" render "scenes/$scene.yaml" --method "$method" -D image.width=320 -D image.height=240 \
        -D shadow.map_size=512 -o "$work/$scene-$method.png" --capture "$trace" >/dev/null 2>&1
      for target in osmesa:llvmpipe osmesa:softpipe; do
        status=0
        "$shadowref" replay "$trace" --on "$target" >"$work/report.txt" 2>"$work/stderr.txt" || status=$?
        if [ "$status" -gt 1 ]; then
          echo "conformance-scenes: replay of $scene $method on $target failed:" >&2
          cat "$work/stderr.txt" >&2
          exit 2
        fi
        rows_of "$scene, $method" "$target" <"$work/report.txt"
      done
    done
  done
} >"$table"

doc=docs/conformance.md
if $check; then
  documented="$work/documented.md"
  doc_section_print conformance-scenes "$doc" >"$documented"
  if ! diff -u "$documented" "$table"; then
    echo "conformance-scenes: $doc differs from what shadowref replay reports (above; run scripts/conformance-scenes.sh)" >&2
    exit 1
  fi
  echo "conformance-scenes: $doc agrees with shadowref replay ($(($(wc -l <"$table") - 2)) rows)"
  exit 0
fi
doc_section_replace conformance-scenes "$table" "$doc"
echo "conformance-scenes: $(($(wc -l <"$table") - 2)) rows written to $doc"
