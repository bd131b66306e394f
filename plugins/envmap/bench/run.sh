#!/usr/bin/env bash
# The envmap speed/accuracy sweep (plugins/envmap/README.md, "Speed and accuracy"): split-sum
# error against the Monte Carlo reference versus milliseconds, per roughness, on
# scenes/ibl_bench.json (a copper sphere under a high-contrast checker environment). shadelab-bench
# writes ibl-rR.csv: RMSE, relMSE, FLIP and the noise of each setting (the spread of a 16-frame
# still's frames, each rendered on its own; `noisy` above SL_NOISE_VISIBLE: tools/bench/README.md,
# "Metrics"). TAA is off: every row is one frame's error, Monte Carlo at N spp per frame not
# accumulated. The load average at the start and end of each roughness goes to stdout and
# ibl-load.txt.
# Usage: plugins/envmap/bench/run.sh [BUILD_DIR] [OUT_DIR]     (about 13 minutes on 2 loaded cores)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
out=${2:-$here}
bench=$build/shadelab-bench
settings=(
  "envmap.samples=512"                       # the defaults: cube 256, 512 samples, 7 levels, LUT 64
  "envmap.samples=16" "envmap.samples=64" "envmap.samples=128" "envmap.samples=1024"
  "envmap.cube_size=32" "envmap.cube_size=64" "envmap.cube_size=128"
  "envmap.mip_count=4" "envmap.mip_count=6"
  "envmap.lut_size=16"
  "envmap.mode=reference envmap.reference_samples=1"
  "envmap.mode=reference envmap.reference_samples=4"
  "envmap.mode=reference envmap.reference_samples=16"
)
args=()
for s in "${settings[@]}"; do args+=(--settings "$s"); done
load() { echo "$(date -u +%FT%RZ), commit $(git -C "$root" rev-parse --short HEAD), load average $(cut -d' ' -f1-3 /proc/loadavg)"; }
: > "$out/ibl-load.txt"
for r in 0.1 0.3 0.6 0.9; do
  echo "roughness $r: start $(load)" | tee -a "$out/ibl-load.txt"
  "$bench" --plugin envmap --scene "$root/scenes/ibl_bench.json" --set "material.ball.roughness=$r" \
    --set envmap.cache=false --set aa.enabled=false --size 320x180 --frames 20 --warmup 3 --reference-accumulate 128 \
    --metric rmse --metric relmse "${args[@]}" --out "$out/ibl-r$r" -q
  echo "roughness $r: end   $(load)" | tee -a "$out/ibl-load.txt"
done
