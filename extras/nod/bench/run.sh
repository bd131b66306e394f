#!/usr/bin/env bash
# Error versus time of nod's quality knob (normals: rest / rigid / exact) with shadelab-bench on
# scenes/nod_standin.json held at a pose (nod.pose_time = 0.5 s: θ = amplitude), against the
# declared reference (normals=exact), with the pivot plane across the skull (y = 1.3 m) and a soft band (0.4 m) and a sharp one (0.1 m).
#   extras/nod/bench/run.sh [BUILD [OUT_DIR]]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../../../build}" && pwd)
out=$(mkdir -p "${2:-$here}" && cd "${2:-$here}" && pwd)
P=nod
# from the repository's root, so the charts name the scene as extras/… (not this machine's path)
cd "$here/../../.."
# core.rerun_passes=true: every pass in every frame (the shadow maps too), the cost of a frame
# while the head moves (a held pose would render the maps once). aa.enabled=false: each frame as
# drawn (TAA's still differs from the one-frame reference by RMSE 0.006, which hides rigid's error
# in the sharp band). FLIP chart: PREFIX-flip.png.
echo "load average: $(cut -d" " -f1-3 /proc/loadavg)"
for blend in 0.4 0.1; do
  "$build/shadelab-bench" --plugin $P --scene extras/nod/scenes/nod_standin.json --size 320x180 \
    --set $P.pose_time=0.5 --set $P.amplitude=25 --set $P.pivot=0,1.3,0 --set $P.blend=$blend \
    --frames 12 --warmup 3 --rounds 3 --set core.rerun_passes=true --set aa.enabled=false --metric rmse --metric flip --no-cache --vary $P.normals=rest,rigid,exact --out "$out/standin_blend$blend"
done
echo "load average: $(cut -d" " -f1-3 /proc/loadavg)"
