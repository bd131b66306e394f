#!/usr/bin/env bash
# Error versus time of voronoi-tiles' quality knobs (search x samples) with shadelab-bench, on
# scenes/tiles.json, against the declared reference (search=exact samples=8).
#   extras/voronoi-tiles/bench/run.sh [BUILD [OUT_DIR]]
# BUILD: the project's build directory (default build/, as ./build.sh makes it; the extras load by name).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../../../build}" && pwd)
out=${2:-$here}
P=voronoi-tiles
args=()
for s in 3x3 radius exact; do for n in 1 2 3 4; do args+=(--settings "$P.search=$s $P.samples=$n"); done; done
"$build/shadelab-bench" --plugin $P --scene "$here/../scenes/tiles.json" --size 320x180 \
  --frames 12 --warmup 3 --rounds 3 --metric rmse --no-cache "${args[@]}" --out "$out/tiles"
