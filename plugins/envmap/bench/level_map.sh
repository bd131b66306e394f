#!/usr/bin/env bash
# envmap's roughness-to-level mapping re-chosen from measured error (issue 16 item 4): the metal
# sphere of levels.sh (specular=dominant, 48², one reference per environment) with
# envmap.level_map = sqrt (level m ↔ perceptual roughness m/(count−1)) and log (α halving per
# level) at 7 and 8 levels, then the prefilter's own knobs from the default (lod_bias 0 instead of 1,
# 2048 samples instead of 512), on courtyard.exr (Debian blender-data; skipped when absent) and the
# procedural sky without its sun.
# Usage: plugins/envmap/bench/level_map.sh [BUILD_DIR] [OUT_DIR] [SIZE] [REFERENCE_FRAMES]
# Writes OUT_DIR/level-map.csv (the columns of levels.csv). ≈ 1–2 min on 2 loaded cores.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
out=${2:-$here}
size=${3:-48}
refs=${4:-16}
envs=(--env sky:0)
hdr=$(blender_hdr courtyard)
[ -n "$hdr" ] && envs=(--env "$hdr" --env sky:0)
# the settings of a sweep item stay set for the next one: each item names everything it changes
sweep="sqrt7=envmap.level_map=sqrt envmap.mip_count=7;log7=envmap.level_map=log envmap.mip_count=7"
sweep+=";log8=envmap.level_map=log envmap.mip_count=8;sqrt8=envmap.level_map=sqrt envmap.mip_count=8"
sweep+=";bias0=envmap.level_map=sqrt envmap.mip_count=7 envmap.lod_bias=0;s2048=envmap.lod_bias=1 envmap.samples=2048"
export SHADELAB_CACHE=${SHADELAB_CACHE:-$(mktemp -d)}
SHADELAB_PLUGIN_PATH="$build/plugins" "$build/plugins/envmap/envmap_bench_terms" --size "$size" \
  --reference-frames "$refs" --material metal --sweep "$sweep" "${envs[@]}" > "$out/level-map.csv"
echo "wrote $out/level-map.csv"
