#!/usr/bin/env bash
# Error versus time of nod's quality knob (normals: rest / rigid / exact) with shadelab-bench on
# scenes/nod_standin.json held at a pose (nod.pose_time = 0.5 s: θ = amplitude), against the
# declared reference (normals=exact), with the pivot plane across the skull (y = 1.3 m) and a soft band (0.4 m) and a sharp one (0.1 m).
#   extras/nod/bench/run.sh [BUILD [OUT_DIR]]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../../../build}" && pwd)
out=${2:-$here}
P=nod
for blend in 0.4 0.1; do
  "$build/shadelab-bench" --plugin $P --scene "$here/../scenes/nod_standin.json" --size 320x180 \
    --set $P.pose_time=0.5 --set $P.amplitude=25 --set $P.pivot=0,1.3,0 --set $P.blend=$blend \
    --frames 12 --warmup 3 --rounds 3 --metric rmse --no-cache --vary $P.normals=rest,rigid,exact --out "$out/standin_blend$blend"
done
