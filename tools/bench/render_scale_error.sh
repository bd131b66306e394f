#!/usr/bin/env bash
# The render scale's error model (core.render_scale, the budget's knob; docs/budget.md): the
# built-in default scene rendered once at 1280x720 and once at each scale s (one frame, linear
# HDR EXR), scaled up bilinearly (oiiotool's triangle filter, as the window's GL_LINEAR present)
# and compared with the full size: RMSE of linear radiance per scale. The figures are what
# core/core_plugin.c declares. A benchmark: it prints figures and asserts nothing.
#   tools/bench/render_scale_error.sh [BUILD_DIR]
set -euo pipefail
BIN=${1:-build}/shadelab
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
for s in 1 0.85 0.7 0.6 0.5 0.35 0.25; do
    w=$(awk -v s="$s" 'BEGIN {printf "%d", 1280 * s + 0.5}') h=$(awk -v s="$s" 'BEGIN {printf "%d", 720 * s + 0.5}')
    "$BIN" --headless -q --size "${w}x${h}" --frames 1 --output "$TMP/s$s.exr"
done
for s in 0.85 0.7 0.6 0.5 0.35 0.25; do
    oiiotool "$TMP/s$s.exr" --resize:filter=triangle 1280x720 -o "$TMP/u$s.exr"
    # --diff exits non-zero when the images differ, which they do
    rms=$( (oiiotool "$TMP/s1.exr" --ch R,G,B "$TMP/u$s.exr" --ch R,G,B --diff 2>&1 || true) |
          sed -n 's/.*RMS error = \([0-9.e-]*\).*/\1/p')
    echo "render scale $s: RMSE $rms (linear radiance, against 1280x720)"
done
