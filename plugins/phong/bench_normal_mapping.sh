#!/usr/bin/env bash
# Cost of normal mapping (README "Can normal mapping be the bottleneck?"): forward-pass median
# of scenes/normalmap_fullscreen.json at 1280x720 in seven configurations, interleaved over
# ROUNDS rounds in one session so that machine load affects all of them alike.
#   plugins/phong/bench_normal_mapping.sh [BUILD_DIR] [ROUNDS]
set -euo pipefail
cd "$(dirname "$0")/../.."
B=${1:-build}; ROUNDS=${2:-5}
ONE=""; for i in 1 2 3 4 5 6 7 8; do ONE="$ONE --set light.p$i.enabled=false"; done
names=(A_lambert_nomap_1L B_lambert_map_1L C_blinn_nomap_1L G_blinn_map_noaa_1L D_blinn_map_1L E_blinn_nomap_9L F_blinn_map_9L)
sets=("--set phong.enabled=false --set normal-map.enabled=false $ONE" "--set phong.enabled=false $ONE"
      "--set normal-map.enabled=false $ONE" "--set phong.specular_aa=false $ONE" "$ONE" "--set normal-map.enabled=false" "")
for r in $(seq 1 "$ROUNDS"); do
  for k in "${!names[@]}"; do
    # shellcheck disable=SC2086
    ms=$("$B/shadelab" --headless --scene scenes/normalmap_fullscreen.json --size 1280x720 --frames 33 --bench ${sets[$k]} 2>&1 |
         awk '/^  forward/{print $2}')
    echo "round $r ${names[$k]} forward_median_ms $ms"
  done
done
