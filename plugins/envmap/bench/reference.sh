#!/usr/bin/env bash
# How fast envmap's reference converges (issue 42): envmap_bench_reference (bench/ibl_reference.c)
# renders six spheres (Lambert; metal α = 0.05 … 1) under Blender's forest.exr and city.exr
# (Debian blender-data; skipped when absent) at 512², `--reference envmap`'s settings with FRAMES
# frames × 64 spp, three seeds, with environment sampling + MIS and with BRDF sampling alone; the
# spread of each sphere's mean across seeds (rel_noise), one render's per-pixel noise
# (pixel_noise) and the time of one render (wall and CPU seconds) go to reference.csv.
# Usage: plugins/envmap/bench/reference.sh [BUILD_DIR] [OUT_DIR] [FRAMES]      ≈ 3 min a row of FRAMES=1
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
out=${2:-$here}
frames=${3:-1}
export SHADELAB_CACHE=${SHADELAB_CACHE:-$(mktemp -d)}
bin="$build/plugins/envmap/envmap_bench_reference"
echo "env,sampling,frames,samples,seconds,cpu_seconds,sphere,mean,rel_noise,pixel_noise" > "$out/reference.csv"
for name in forest city; do
  hdr=$(blender_hdr "$name")
  [ -n "$hdr" ] || { echo "$name.exr (Debian blender-data) not installed: skipped"; continue; }
  for sampling in "" --no-env-sampling; do
    SHADELAB_PLUGIN_PATH="$build/plugins" "$bin" --env "$hdr" --frames "$frames" --samples 64 --seeds 3 $sampling |
      tail -n +2 >> "$out/reference.csv"
  done
done
echo "wrote $out/reference.csv"
