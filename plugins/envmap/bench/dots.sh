#!/usr/bin/env bash
# What a small bright sun looks like through specular=filtered's sample set: the α = 0.2 sphere of
# cycles.sh's metal row under Blender's MAP.exr (default city: its sun ≈ 34 000), exposed EV below
# the display (default −4.3, 1/20: the highlight does not clip), 480x96 on OSMesa, the sphere's
# highlight cropped (40x40 pixels) and enlarged 8x. Two panels: the first frame (aa off, what
# every frame in motion shows) and the TAA still of 16 frames (the set turned frame by frame).
# Writes bench/dots-MAP.png.
# Usage: plugins/envmap/bench/dots.sh [BUILD_DIR] [MAP] [EV]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
map=${2:-city}
ev=${3:--4.3}
hdr=$(blender_hdr "$map")
[ -n "$hdr" ] || { echo "dots.sh: Blender's $map.exr is not installed (Debian blender-data)" >&2; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
metal_row "$map" "$hdr" > "$tmp/row.json"
shot() { # NAME SETTINGS...: render and crop the α = 0.2 sphere's highlight
  local name=$1; shift
  SHADELAB_PLUGIN_PATH="$build/plugins" "$build/shadelab" --headless -q --scene "$tmp/row.json" --size 480x96 \
    --plugin tonemap --set tonemap.exposure="$ev" --set envmap.specular=filtered "$@" --output "$tmp/$name.png"
  oiiotool "$tmp/$name.png" --cut 40x40+150+10 --resize:filter=box 320x320 -o "$tmp/crop-$name.png"
}
shot first --set aa.enabled=false --frames 1
shot still
oiiotool "$tmp/crop-first.png" "$tmp/crop-still.png" --mosaic:pad=4 2x1 -o "$here/dots-$map.png"
echo "$here/dots-$map.png: first frame | TAA still ($map, $ev EV)" >&2
