#!/usr/bin/env bash
# The accuracy table of docs/shadow-maps.md ("Accuracy, measured") from the command line, as a user
# gets it: per cell one `shadowref render SCENE --method shadowmap|tsm -D shadow.map_size=N
# --oracle` with the row's anti-self-shadowing -D options, its "% wrong" (the map tested at the
# oracle's surface points) against the cell. The table itself is bench/shadow_map_accuracy's; this
# shows the command line reproduces it.
#   scripts/oracle-table.sh [--sizes N,N,...] [BUILD_DIR]    default: every column; BUILD_DIR build
# Prints one line per cell (documented, measured); exits 1 when a cell differs, 2 when a render
# fails or the table cannot be read.
set -euo pipefail
cd "$(dirname "$0")/.."
sizes=""
if [ "${1:-}" = "--sizes" ]; then
  sizes=",$2,"
  shift 2
fi
build_dir=${1:-build}
shadowref="$build_dir/shadowref"
[ -x "$shadowref" ] || { echo "oracle-table: no $shadowref (build it first)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The table's rows, "scene|method|anti|v128|v256|...", and its sizes from the header.
doc=docs/shadow-maps.md
awk -F'|' '
  /^\| scene \| method \| anti-self-shadowing \|/ { inside = 1; for (i = 5; i < NF; ++i) { s = $i; gsub(/[ ²]/, "", s); head = head (head ? " " : "") s }; print "sizes " head; next }
  inside && /^\| ---/ { next }
  inside && /^\|/ { row = ""; for (i = 2; i < NF; ++i) { c = $i; gsub(/^ +| +$/, "", c); row = row (i > 2 ? "|" : "") c }; print row; next }
  inside { exit }
' "$doc" >"$work/table"
read -r _ header <"$work/table"
[ -n "$header" ] || { echo "oracle-table: no accuracy table in $doc" >&2; exit 2; }
read -ra columns <<<"$header"

differ=0
cells=0
while IFS='|' read -r scene method anti values; do
  args=()
  case $scene in
    outdoor) file=scenes/outdoor.yaml ;;
    room) file=scenes/room.yaml ;;
    room-spot) file=scenes/room.yaml
      args+=(-D lights.0.type=spot -D "lights.0.direction=[0, -1, 0]" -D lights.0.spot_cutoff=70) ;;
    *) echo "oracle-table: unknown scene '$scene' in $doc" >&2; exit 2 ;;
  esac
  case $method in
    standard) args+=(--method shadowmap)
      # The outdoor standard rows are the scene box's map, as the table's text says.
      [ "$scene" = outdoor ] && args+=(-D shadow.fit=scene) ;;
    "cube maps") args+=(--method shadowmap) ;;
    TSM) args+=(--method tsm) ;;
    *) echo "oracle-table: unknown method '$method' in $doc" >&2; exit 2 ;;
  esac
  case $anti in
    offset) ;;  # the default polygon offset (1.1, 4)
    bias) args+=(-D shadow.offset_factor=0 -D shadow.offset_units=0 -D shadow.bias=0.0001) ;;
    backfaces) args+=(-D shadow.offset_factor=0 -D shadow.offset_units=0 -D shadow.back_faces_only=true) ;;
    none) args+=(-D shadow.offset_factor=0 -D shadow.offset_units=0) ;;
    *) echo "oracle-table: unknown anti-self-shadowing '$anti' in $doc" >&2; exit 2 ;;
  esac
  IFS='|' read -ra documented <<<"$values"
  for k in "${!columns[@]}"; do
    size=${columns[$k]}
    [ -z "$sizes" ] || [[ $sizes == *",$size,"* ]] || continue
    if ! "$shadowref" render "$file" "${args[@]}" -D shadow.map_size="$size" --oracle -o "$work/frame.png" \
      >"$work/out.txt" 2>"$work/err.txt"; then
      echo "oracle-table: $scene $method $anti $size²: render failed:" >&2
      cat "$work/err.txt" >&2
      exit 2
    fi
    measured=$(sed -n 's/^  map test at .*, \([0-9.]*\) % wrong$/\1/p' "$work/out.txt" | head -1)
    cells=$((cells + 1))
    verdict=same
    if [ "$measured" != "${documented[$k]}" ]; then
      verdict=DIFFERS
      differ=$((differ + 1))
    fi
    printf '%-9s %-9s %-9s %5s²  documented %6s  measured %6s  %s\n' "$scene" "$method" "$anti" "$size" \
      "${documented[$k]}" "$measured" "$verdict"
  done
done < <(tail -n +2 "$work/table")
[ "$cells" -gt 0 ] || { echo "oracle-table: no cell chosen" >&2; exit 2; }
if [ "$differ" -gt 0 ]; then
  echo "oracle-table: $differ of $cells cells of $doc differ from shadowref render --oracle" >&2
  exit 1
fi
echo "oracle-table: all $cells cells of $doc reproduced by shadowref render --oracle"
