#!/usr/bin/env bash
# The trade, measured: runs the sweep bench/tradeoffs.sweep.yaml (docs/sweeps.md) and regenerates
# docs/tradeoffs.md's results table, bench/results/tradeoffs.csv and docs/images/tradeoff-*.png.
#   bash scripts/setup.sh build && bash scripts/bench-tradeoffs.sh [BUILD_DIR] [shadowref sweep options...]
# The records go to out/sweeps/tradeoffs/ and a job with a complete record is not run again: the
# script picks up where an interrupted run stopped. To measure everything anew, remove that folder.
# Options after BUILD_DIR go to `shadowref sweep` (e.g. --threads 2); the jobs run one after
# another so that no job is timed while another competes for the cores.
set -euo pipefail
cd "$(dirname "$0")/.."

build=${1:-build}
shift || true
if [ ! -f "$build/build.ninja" ]; then
  echo "bench-tradeoffs: no build in '$build'; run: bash scripts/setup.sh $build" >&2
  exit 2
fi
cmake --build "$build" --target shadowref >/dev/null
spec=bench/tradeoffs.sweep.yaml
out=out/sweeps/tradeoffs

start=$(date +%s)
"$build/shadowref" sweep "$spec" --out "$out" "$@"
echo "bench-tradeoffs: the jobs took $(( $(date +%s) - start )) s" >&2
mkdir -p bench/results docs/images
"$build/shadowref" sweep "$spec" --out "$out" --merge --csv bench/results/tradeoffs.csv --plots "$out/plots" \
  --table "$out/table.md"

# The table replaces what lies between the markers of docs/tradeoffs.md; the rest is hand-written.
awk -v table="$out/table.md" '
  /<!-- sweep-table: begin -->/ { print; while ((getline line < table) > 0) print line; skip = 1; next }
  /<!-- sweep-table: end -->/ { skip = 0 }
  !skip' docs/tradeoffs.md > docs/tradeoffs.md.new
mv docs/tradeoffs.md.new docs/tradeoffs.md
rm -f docs/images/tradeoff-*.png
for png in "$out"/plots/plot-*.png; do
  [ -e "$png" ] || continue
  name=$(basename "$png" .png)
  cp "$png" "docs/images/tradeoff-${name#plot-}.png"
done
echo "bench-tradeoffs: wrote bench/results/tradeoffs.csv, docs/tradeoffs.md, docs/images/tradeoff-*.png" >&2
