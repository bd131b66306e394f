#!/usr/bin/env bash
# Error versus time of displacement's knobs with shadelab-bench (llvmpipe, glFinish timing):
#  waves:          true displacement, displacement.edge_px swept, against edge_px=1 (the declared
#                  reference: finest tessellation, level cap 48);
#  waves_parallax: POM layers and plain parallax against the same displaced surface
#                  (--reference-settings: the material also gets `displace`, which wins).
# The flat polygon's error (no relief) is the README's baseline.
#   extras/displacement/bench/run.sh [BUILD [OUT_DIR]]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../../../build}" && pwd)
out=${2:-$here}
B="$build/shadelab-bench --plugin displacement --size 320x180 --frames 6 --warmup 2 --rounds 2 --metric rmse --no-cache"
$B --scene "$here/../scenes/waves.json" --set spotlight-shadow.map_size=1024 \
   $(for e in 2 4 8 16 32 64; do printf -- '--settings displacement.edge_px=%s ' $e; done) --out "$out/waves_tess"
$B --scene "$here/../scenes/waves_parallax.json" --set spotlight-shadow.map_size=1024 \
   --reference-settings "material.waves.displace=0.06 displacement.edge_px=1" \
   --settings "material.waves.parallax=0" \
   $(for n in 4 8 16 32 64; do printf -- '--settings displacement.pom_steps=%s ' $n; done) \
   --settings displacement.parallax=plain --out "$out/waves_parallax"
