#!/usr/bin/env bash
# Error versus time of voronoi-tiles' quality knobs (search x samples) with shadelab-bench, on
# scenes/tiles.json, against the declared reference (search=exact samples=8).
#   extras/voronoi-tiles/bench/run.sh PREFIX EXTRAS_BUILD [OUT_DIR]
# PREFIX: an installed shadelab (bin/shadelab-bench); EXTRAS_BUILD: the extras' build directory.
set -eu
prefix=$(cd "$1" && pwd) build=$(cd "$2" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
out=${3:-$here}
export SHADELAB_PLUGIN_PATH=$build/voronoi-tiles/plugins
P=voronoi-tiles
args=()
for s in 3x3 radius exact; do for n in 1 2 3 4; do args+=(--settings "$P.search=$s $P.samples=$n"); done; done
"$prefix/bin/shadelab-bench" --plugin $P --scene "$here/../scenes/tiles.json" --size 320x180 \
  --frames 12 --warmup 3 --rounds 3 --metric rmse --no-cache "${args[@]}" --out "$out/tiles"
