#!/usr/bin/env bash
# Runs the OSMesa conformance tests with softpipe and llvmpipe and regenerates the agreement
# table in docs/conformance.md (between the conformance-table markers).
#   scripts/conformance-report.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/doc-section.sh
build_dir=${1:-build}
cmake --build "$build_dir" --target conformance_tests >/dev/null
binary="$build_dir/tests/conformance_tests"
rows=$(mktemp)
trap 'rm -f "$rows"' EXIT
for driver in softpipe llvmpipe; do
  # The run's own pass/fail is CI's business; the table shows every case either way.
  GALLIUM_DRIVER=$driver SHADOWREF_CONFORMANCE_REPORT="$rows" "$binary" >/dev/null || true
done
table=$(mktemp)
trap 'rm -f "$rows" "$table"' EXIT
{
  echo "| case | driver | pixels | edge pixels | stencil equal | stencil diff on / off edge | max depth diff / allowed (24-bit units) | max colour diff / allowed (1/255) | expectation | note |"
  echo "|---|---|---|---|---|---|---|---|---|---|"
  sort -s -t'|' -k2,2 "$rows"
} >"$table"
doc=docs/conformance.md
doc_section_replace conformance-table "$table" "$doc"
echo "conformance-report: $(wc -l <"$rows") rows written to $doc"
