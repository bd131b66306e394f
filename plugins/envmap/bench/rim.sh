#!/usr/bin/env bash
# Where the split sum's error on a real HDR comes from, and what is left of the highest fis setting
# (issue 16): envmap_bench_rim (bench/ibl_rim.c) on Blender's courtyard.exr (Debian blender-data),
# the bench's 48² metal sphere, every pixel against a C quadrature of the GGX integral (no GL).
#   rim.csv       128 × 128-point quadrature per integral; the plugin's GL renders compared with it
#                 (reference at 32 and 128 frames, mirror, dominant, fis accumulated)   ≈ 4 min
#   rim-still.csv TAA stills (reference, default, dominant, fis, hybrid) vs the quadrature
#                 averaged over the still's jitter points (96 × 96 points)              ≈ 6 min
#   rim-taps.csv  CPU only, 40 × 40 points: the split sum's variants incl. K taps along the plane
#                 of incidence (footprint assembly)                                     ≈ 8 min
# Usage: plugins/envmap/bench/rim.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
out=${2:-$here}
hdr=$(blender_hdr courtyard)
[ -n "$hdr" ] || { echo "courtyard.exr (Debian blender-data) not installed: nothing to measure"; exit 0; }
export SHADELAB_CACHE=${SHADELAB_CACHE:-$(mktemp -d)}
bin="$build/plugins/envmap/envmap_bench_rim"
SHADELAB_PLUGIN_PATH="$build/plugins" "$bin" --env "$hdr" --nu 128 --nphi 128 --gl --no-taps > "$out/rim.csv"
# the TAA still (aa on, 16 jittered frames) against the quadrature averaged over the same jitter
# points: what the viewer shows at rest, checked without the plugin's reference   ≈ 6 min
SHADELAB_PLUGIN_PATH="$build/plugins" "$bin" --env "$hdr" --nu 96 --nphi 96 --still > "$out/rim-still.csv"
[ "${TAPS:-1}" = 1 ] && "$bin" --env "$hdr" --nu 40 --nphi 40 > "$out/rim-taps.csv"
echo "wrote $out/rim.csv${TAPS:+ rim-taps.csv}"
