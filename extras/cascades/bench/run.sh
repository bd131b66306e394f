#!/usr/bin/env bash
# Error versus time of cascaded shadow maps on scenes/long_floor.json (a 200 m floor, the camera
# 1.7 m above it) with shadelab-bench, against the declared reference: one 8192² map fitted to
# the whole scene (cascades.enabled=false spotlight-shadow.map_size=8192), same PCF 3×3 filter.
# Baseline: one fitted map of the same total memory as each cascade setting (N maps of s² =
# one map of (s·√N)²). always_render=true: every timed frame renders the maps, as a moving
# camera does (a still camera skips the pass).
#   extras/cascades/bench/run.sh PREFIX EXTRAS_BUILD [OUT_DIR]
# PREFIX: an installed shadelab (bin/shadelab-bench); EXTRAS_BUILD: the extras' build directory.
set -eu
prefix=$(cd "$1" && pwd) build=$(cd "$2" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
out=${3:-$here}
export SHADELAB_PLUGIN_PATH=$build/cascades/plugins
args=()
for s in 512 1024 2048; do
  for n in 2 3 4; do args+=(--settings "cascades.count=$n spotlight-shadow.map_size=$s"); done
done
for m in 724 887 1024 1448 1774 2048 2896 3547 4096; do
  args+=(--settings "cascades.enabled=false spotlight-shadow.map_size=$m")
done
"$prefix/bin/shadelab-bench" --plugin cascades --scene "$here/../scenes/long_floor.json" --size 320x180 \
  --set spotlight-shadow.always_render=true --frames 12 --warmup 3 --rounds 3 --metric rmse --no-cache \
  "${args[@]}" --out "$out/long_floor"
