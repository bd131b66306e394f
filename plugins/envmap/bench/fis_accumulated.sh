#!/usr/bin/env bash
# The highest fis setting accumulated (issue 16's "highest FIS ≤ 0.03" target): fis N = 32 with
# irradiance=convolved, 32 accumulated frames, against the reference (32 × 64 spp) — the
# methods.sh "fis32-accumulated" rows — with the per-sample footprint over all N·F samples of the
# accumulated estimate ("new", the plugin's rule) and over one frame's N ("old": the same with
# fis_lod_bias raised by ½ log2 32 = 2.5, which is exactly the former rule), metal and dielectric,
# on courtyard.exr (Debian blender-data; skipped when absent) and the sky without its sun.
# Usage: plugins/envmap/bench/fis_accumulated.sh [BUILD_DIR] [OUT_DIR]   (≈ 30 min on 2 loaded cores)
# Writes OUT_DIR/fis-accumulated.csv (the columns of levels.csv).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
out=${2:-$here}
envs=(sky:0)
hdr=$(blender_hdr courtyard)
[ -n "$hdr" ] && envs=("$hdr" sky:0)
sweep="old=envmap.specular=fis envmap.fis_samples=32 envmap.irradiance=convolved envmap.fis_lod_bias=1.5;new=envmap.fis_lod_bias=-1"
export SHADELAB_CACHE=${SHADELAB_CACHE:-$(mktemp -d)}
first=1
for e in "${envs[@]}"; do for m in metal dielectric; do
  SHADELAB_PLUGIN_PATH="$build/plugins" "$build/plugins/envmap/envmap_bench_terms" --size 48 --reference-frames 32 \
    --accumulate 32 --material "$m" --sweep "$sweep" --env "$e" | { [ $first = 1 ] && cat || tail -n +2; }
  first=0
done; done > "$out/fis-accumulated.csv"
echo "wrote $out/fis-accumulated.csv"
