#!/usr/bin/env bash
# Installs the Python package (cmake --install, component python) into a fresh temporary prefix
# and imports it from there, away from the build tree: it must be the installed copy that loads,
# and it must render (the module carries the library in itself: nothing else to find).
#   python/tests/install.sh BUILD_DIR PYTHON SITE_DIR_UNDER_PREFIX
set -euo pipefail
build=$(cd "$1" && pwd)
python=$2
site=$3
cd "$(dirname "$0")/../.."
root=$PWD
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build" --prefix "$prefix/usr" --component python > /dev/null
test -f "$prefix/usr/$site/shadowref/__init__.pyi"
cd "$prefix"
PYTHONPATH="$prefix/usr/$site" "$python" - "$prefix" "$root" <<'PY'
import os, sys
prefix, root = sys.argv[1], sys.argv[2]
import shadowref
assert shadowref.__file__.startswith(prefix), shadowref.__file__
frame = shadowref.render(os.path.join(root, "scenes/minimal.yaml"), size=(32, 24), method="zfail", threads=1)
assert frame.stencil.shape == (24, 32), frame.stencil.shape
assert frame.color.shape == (24, 32, 4)
print("installed", shadowref.__version__, "at", os.path.dirname(shadowref.__file__))
PY
