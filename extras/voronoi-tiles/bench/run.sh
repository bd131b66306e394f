#!/usr/bin/env bash
# Error versus time of voronoi-tiles' quality knobs (search x samples) with shadelab-bench, on
# scenes/tiles.json, against the declared reference (search=exact samples=8). Each frame as drawn
# (aa.enabled=false): TAA's converged still would average away the aliasing the samples knob removes.
# Writes OUT_DIR/tiles.{csv,json,png} and tiles-flip.png (FLIP), with each setting's noise.
#   extras/voronoi-tiles/bench/run.sh [BUILD [OUT_DIR]]
# BUILD: the project's build directory (default build/, as ./build.sh makes it; the extras load by name).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../../../build}" && pwd)
out=$(mkdir -p "${2:-$here}" && cd "${2:-$here}" && pwd)
P=voronoi-tiles
# from the repository's root, so the charts name the scene as extras/… (not this machine's path)
cd "$here/../../.."
args=()
for s in 3x3 radius exact; do for n in 1 2 3 4; do args+=(--settings "$P.search=$s $P.samples=$n"); done; done
echo "load average: $(cut -d" " -f1-3 /proc/loadavg)"
"$build/shadelab-bench" --plugin $P --scene extras/voronoi-tiles/scenes/tiles.json --size 320x180 \
  --set aa.enabled=false --frames 12 --warmup 3 --rounds 3 --metric rmse --metric flip --no-cache "${args[@]}" --out "$out/tiles"
echo "load average: $(cut -d" " -f1-3 /proc/loadavg)"
