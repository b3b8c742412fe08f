#!/usr/bin/env bash
# The trade, measured: builds the bench program bench/tradeoffs (the target tradeoffs of
# a shadowref build), runs every configuration (ten minutes or so on a 2-core machine), and
# writes bench/results/tradeoffs.csv, docs/tradeoffs.md and docs/images/tradeoff-*.png.
#   bash scripts/setup.sh build && bash scripts/bench-tradeoffs.sh [BUILD_DIR] [tradeoffs options...]
# Options: --frames N (timed frames a probe, default 5), --rounds N (probes of every configuration,
# each round a step further down the list, default 5), --threads N (render threads, default 1),
# --samples N (soft reference rays per pixel, default 256), --only GROUP (counting, soft, houses,
# lights, map_size, pcf, bias, depth, far; the outputs then hold that group alone).
set -euo pipefail
cd "$(dirname "$0")/.."

build=${1:-build}
shift || true
if [ ! -f "$build/build.ninja" ]; then
  echo "bench-tradeoffs: no build in '$build'; run: bash scripts/setup.sh $build" >&2
  exit 2
fi
build=$(cd "$build" && pwd)
cmake --build "$build" --target tradeoffs >/dev/null

commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
git diff --quiet HEAD -- src bench/tradeoffs tests/support scenes 2>/dev/null || commit="$commit (with uncommitted changes)"
mkdir -p bench/results docs/images
"$build/bench/tradeoffs" --commit "$commit" "$@"

if ! command -v gnuplot >/dev/null; then
  echo "bench-tradeoffs: gnuplot not found (scripts/setup.sh installs gnuplot-nox); plots not drawn" >&2
  exit 0
fi
terminal='set terminal pngcairo size 960,620 font "DejaVu Sans,10"'
axes='set grid; set key top right; set logscale x; set xlabel "median CPU time per frame (ms; 400x320, 1 render thread)"'
for data in bench/results/plot-*.dat; do
  case "$data" in *-front.dat) continue ;; esac
  name=$(basename "$data" .dat)
  name=${name#plot-}
  # Errors spanning decades (shadow maps) read best on a log scale; exact methods have error 0.
  yscale='set yrange [0:*]'
  awk '!/^#/ && $2 <= 0 { zero = 1 } END { exit zero }' "$data" && yscale='set logscale y'
  gnuplot <<EOF
$terminal
set output "docs/images/tradeoff-$name.png"
$axes
$yscale
set title "$name: shadow error against time; the line is the Pareto front (labelled)"
set ylabel "error: mean |visibility - reference| (%)"
set offsets graph 0.02, graph 0.3, graph 0.05, graph 0.02
plot "$data" using 1:2 with points pt 7 ps 1.3 lc rgb "#3060a0" title "configurations", \
     "bench/results/plot-$name-front.dat" using 1:2 with linespoints lw 2 pt 6 ps 2.2 lc rgb "#c03020" title "Pareto front", \
     "bench/results/plot-$name-front.dat" using 1:2:3 with labels left offset 0.9,0.5 font ",8" tc rgb "#303030" notitle
EOF
done
if [ -s bench/results/series-map-size.dat ] && [ "$(wc -l < bench/results/series-map-size.dat)" -gt 1 ]; then
  gnuplot <<EOF
$terminal
set output "docs/images/tradeoff-map-size.png"
set grid; set key top center
set title "outdoor: standard shadow map and TSM against map size [Hempe 2004, §6.1]"
set logscale x 2; set xlabel "map size (texels per side)"
set ylabel "wrongly shadowed or lit pixels (%)"
set y2label "median CPU time per frame (ms)"; set y2tics; set logscale y2; set ytics nomirror
plot "bench/results/series-map-size.dat" using 1:3 with linespoints lw 2 pt 7 title "standard: error", \
     "" using 1:5 with linespoints lw 2 pt 5 title "TSM: error", \
     "" using 1:2 axes x1y2 with linespoints dt 2 pt 6 title "standard: time", \
     "" using 1:4 axes x1y2 with linespoints dt 2 pt 4 title "TSM: time"
EOF
fi
if [ "$(grep -vc '—' bench/results/series-houses.dat)" -gt 1 ]; then
  gnuplot <<EOF
$terminal
set output "docs/images/tradeoff-houses.png"
set grid; set key top left; set datafile missing "—"
set title "city, one light: time per frame against houses [Kuhn 2016, §5.4.1]"
set xlabel "houses"; set ylabel "median CPU time per frame (ms)"
plot "bench/results/series-houses.dat" using 1:2 with linespoints lw 2 title "random models, no shadows", \
     "" using 1:3 with linespoints lw 2 title "random models, z-pass", \
     "" using 1:4 with linespoints lw 2 title "Haus01, no shadows", \
     "" using 1:5 with linespoints lw 2 title "Haus01, z-pass"
EOF
fi
if [ "$(grep -vc '—' bench/results/series-lights.dat)" -gt 1 ]; then
  gnuplot <<EOF
$terminal
set output "docs/images/tradeoff-lights.png"
set grid; set key top left; set datafile missing "—"
set title "city, 16 x Haus02: time per frame against lights [Kuhn 2016, §5.4.1]"
set xlabel "lights"; set ylabel "median CPU time per frame (ms)"
plot "bench/results/series-lights.dat" using 1:2 with linespoints lw 2 title "no shadows", \
     "" using 1:3 with linespoints lw 2 title "z-pass"
EOF
fi
echo "bench-tradeoffs: wrote bench/results/tradeoffs.csv, docs/tradeoffs.md, docs/images/tradeoff-*.png" >&2
