#!/usr/bin/env bash
# Error versus time of displacement's knobs with shadelab-bench (llvmpipe, glFinish timing):
#  waves:          true displacement, displacement.edge_px swept, against edge_px=1 (the declared
#                  reference: finest tessellation, level cap 48);
#  waves_parallax: POM layers and plain parallax against the same displaced surface
#                  (--reference-settings: the material also gets `displace`, which wins).
# The flat polygon's error (no relief) is the README's baseline. Each writes PREFIX.{csv,json},
# PREFIX.png (RMSE) and PREFIX-flip.png (FLIP), with each setting's noise. Each frame as drawn
# (aa.enabled=false): TAA's still differs from the one-frame reference by RMSE 0.001, a floor that
# hid the finer edges' differences. core.rerun_passes=true: the shadow map (the displaced surface
# tessellated again) in every frame, the cost of a frame while the sun or the surface moves.
#   extras/displacement/bench/run.sh [BUILD [OUT_DIR]]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../../../build}" && pwd)
out=$(mkdir -p "${2:-$here}" && cd "${2:-$here}" && pwd)
# from the repository's root, so the charts name the scenes as extras/… (not this machine's path)
cd "$here/../../.."
echo "load average: $(cut -d" " -f1-3 /proc/loadavg)"
B="$build/shadelab-bench --plugin displacement --size 320x180 --frames 12 --warmup 3 --rounds 3 --set aa.enabled=false --set core.rerun_passes=true --metric rmse --metric flip --no-cache"
$B --scene extras/displacement/scenes/waves.json --set spotlight-shadow.map_size=1024 \
   $(for e in 2 4 8 16 32 64; do printf -- '--settings displacement.edge_px=%s ' $e; done) --out "$out/waves_tess"
$B --scene extras/displacement/scenes/waves_parallax.json --set spotlight-shadow.map_size=1024 \
   --reference-settings "material.waves.displace=0.06 displacement.edge_px=1" \
   --settings "material.waves.parallax=0" \
   $(for n in 4 8 16 32 64; do printf -- '--settings displacement.pom_steps=%s ' $n; done) \
   --settings displacement.parallax=plain --out "$out/waves_parallax"
echo "load average: $(cut -d" " -f1-3 /proc/loadavg)"
