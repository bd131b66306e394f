#!/usr/bin/env bash
# OpenImageIO is opened only when an image file other than a plain JPEG/PNG/EXR is read or a format
# other than PNG is written (core/image/image.h: its ~250 libraries cost every process start ≈ 0.5 s):
# the bare scene rendered to a PNG, the built-in default (envmap's sky, no file), a scene with a PNG
# texture and envmap with an EXR file (both decoded natively, image_native.c; a DWAB one through the
# OpenEXR module shadelab-exr.so) map no libOpenImageIO;
# an EXR output and envmap with a Radiance .hdr file do, and their images are written. Checked with the dynamic loader's own log (LD_DEBUG=files), not with timings.
#   usage: cli_lazy_oiio.sh SHADELAB SCENES_DIR OUTDIR
set -u
exe=$1 scenes=$2 out=$3
mkdir -p "$out"
. "$(dirname "$0")/cli_check.sh"
# The decoded-image cache (core/image/image_cache.c) would let a .hdr read in an earlier run (every
# test shares the build's test-cache) load without the module: off here, so that what is checked is
# which files need OpenImageIO; the cache's own case is at the end, with a directory of its own.
export SHADELAB_IMAGE_CACHE=0
loads_oiio() { # the whole log first: grep -q would stop reading and SIGPIPE the run
    local log
    log=$(LD_DEBUG=files "$exe" --headless --size 32x18 --frames 1 "$@" 2>&1)
    grep -q "file=libOpenImageIO" <<<"$log"
}
check test "$("$exe" --version)" != ""
check eval '! loads_oiio --scene "$scenes/basic.json" --output "$out/basic.png"'
check test -s "$out/basic.png"
check eval '! loads_oiio --output "$out/default.png"'
check test -s "$out/default.png"
check loads_oiio --scene "$scenes/basic.json" --output "$out/basic.exr"
check test -s "$out/basic.exr"
# a texture file: the PNG just written, as a material's base colour map
cat > "$out/textured.json" <<JSON
{"materials": [{"name": "m", "model": "lambert", "base_color_map": "basic.png"}],
 "nodes": [{"name": "s", "mesh": {"primitive": "sphere", "radius": 1}, "material": "m"}],
 "lights": [{"type": "directional", "direction": [0, -1, -1], "color": [1, 1, 1]}]}
JSON
check eval '! loads_oiio --scene "$out/textured.json" --output "$out/textured.png"'
check test -s "$out/textured.png"
# envmap with an image file, read through host->read_image (SDK 1.10): an EXR natively, a .hdr
# through OpenImageIO's module
check loads_oiio --scene "$scenes/basic.json" --output "$out/basic.hdr"
check test -s "$out/basic.hdr"
for map in basic.exr basic.hdr; do
  cat > "$out/env_$map.json" <<JSON
{"plugins": ["ggx", "envmap"], "environment": {"map": "$map"},
 "materials": [{"name": "m", "model": "ggx", "base_color": [0.8, 0.8, 0.8], "roughness": 0.5}],
 "nodes": [{"name": "s", "mesh": {"primitive": "sphere", "radius": 1}, "material": "m"}],
 "lights": []}
JSON
done
check eval '! loads_oiio --scene "$out/env_basic.exr.json" --output "$out/env_exr.png"'
check test -s "$out/env_exr.png"
# a DWAB-compressed EXR (as blender-data's environments are): OpenEXRCore cannot decode it, OpenEXR's
# C++ library does, in its own small module (shadelab-exr.so), still without OpenImageIO
if command -v oiiotool >/dev/null; then
  check oiiotool "$out/basic.exr" --compression dwab -o "$out/dwab.exr"
  sed 's/basic\.exr/dwab.exr/' "$out/env_basic.exr.json" > "$out/env_dwab.json"
  check eval '! loads_oiio --scene "$out/env_dwab.json" --output "$out/env_dwab.png"'
  check test -s "$out/env_dwab.png"
  msg=$("$exe" --headless --size 32x18 --frames 1 -v --scene "$out/env_dwab.json" --output "$out/env_dwab.png" 2>&1)
  check grep -q "image module: .*shadelab-exr.so" <<<"$msg"
fi
check loads_oiio --scene "$out/env_basic.hdr.json" --output "$out/env.png"
msg=$("$exe" --headless --size 32x18 --frames 1 -v --scene "$out/env_basic.hdr.json" --output "$out/env.png" 2>&1)
check grep -q "image module: .*shadelab-oiio.so" <<<"$msg"
check grep -q "basic.hdr" <<<"$msg"
# with the cache on, in a fresh directory: the first run decodes the .hdr through the module and keeps
# it; the second loads it from the cache and opens no OpenImageIO
rm -rf "$out/image-cache"
cached() { SHADELAB_IMAGE_CACHE=1 SHADELAB_CACHE="$out/image-cache" loads_oiio "$@"; }
check cached --scene "$out/env_basic.hdr.json" --output "$out/env_c1.png"
check test "$(ls "$out/image-cache/images" | grep -c '^img-.*\.bin$')" = 1
check eval '! cached --scene "$out/env_basic.hdr.json" --output "$out/env_c2.png"'
check cmp "$out/env_c1.png" "$out/env_c2.png"
echo "cli_lazy_oiio: $pass passed, $fail failed"
[ $fail -eq 0 ]
