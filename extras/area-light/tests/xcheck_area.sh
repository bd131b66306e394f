#!/usr/bin/env bash
# Cycles (through shadelab-xcheck) against this plugin on a Lambert plane under a rectangle and a
# disk light, where the plugin evaluates Lambert's formula exactly: the area light's conversion to
# Blender (power = 4·L·A, its orientation and shape) must agree within Cycles' noise.
#   usage: xcheck_area.sh SHADELAB_XCHECK PLUGIN_DIR SCENE CACHE_DIR
# Exit 77 (skipped) when Blender is not installed.
set -uo pipefail
XC=$1 PLUGINS=$2 SCENE=$3 CACHE=$4
OUT=$(mktemp -d "${TMPDIR:-/tmp}/shadelab-xcheck-area.XXXXXX")
trap 'rm -rf "$OUT"' EXIT
SHADELAB_PLUGIN_PATH=$PLUGINS "$XC" --size 96x96 --samples 64 --cache "$CACHE" --out "$OUT/x" \
  --max-rel-rms 0.03 "$SCENE"
status=$?
[ $status = 77 ] && echo "SKIPPED: Blender is not installed"
exit $status
