#!/usr/bin/env bash
# Extras test: install shadelab into a fresh temporary prefix, configure and build extras/
# against it exactly as a third party would (find_package(shadelab), no core headers), and run
# the modules' own tests through ctest.
#   usage: extras.sh SOURCE_DIR BUILD_DIR [CMAKE]
set -euo pipefail
SRC=$1 BUILD=$2 CMAKE=${3:-cmake}
CTEST=$(dirname "$CMAKE")/ctest; [ -x "$CTEST" ] || CTEST=ctest
T=$(mktemp -d "${TMPDIR:-/tmp}/shadelab-extras.XXXXXX")
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
export SHADELAB_PLUGIN_PATH= SHADELAB_SHADER_DIR=
. "$(dirname "$0")/sdk_prefix.sh"

echo "== install shadelab into $T/prefix"
sl_install_prefix "$BUILD" "$T/prefix" "$T" "$CMAKE" || fail "install"

echo "== configure and build extras/ against the installed SDK only"
"$CMAKE" -S "$SRC/extras" -B "$T/build" -DCMAKE_PREFIX_PATH="$T/prefix" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  >"$T/configure.log" 2>&1 || { cat "$T/configure.log"; fail "configure extras"; }
"$CMAKE" --build "$T/build" -j2 >"$T/build.log" 2>&1 || { cat "$T/build.log"; fail "build extras"; }
# No core header: everything a module includes from shadelab comes from the installed prefix
# (<shadelab/...>); a quoted include of the core's tree would not resolve there, and a path into
# the source tree's core/ is refused here as well.
if grep -rnE '#include +"[^"]*(core|plugins)/' "$SRC/extras" --include='*.c' --include='*.h' --include='*.cpp'; then
  fail "an extra includes a core or bundled plugin source file"
fi

echo "== the modules' tests"
(cd "$T/build" && "$CTEST" --output-on-failure -j2) || fail "extras tests"
echo "PASS: extras built against the installed SDK and their tests passed"
