#!/usr/bin/env bash
# Hostile input (issue 14): every case ends in bounded time (timeout 300 s, a hang guard a loaded machine does not reach; 124 = a hang) with a
# clear message naming the input, and a failed run leaves an existing output file untouched.
# Families: special files as the scene (/dev/zero, /dev/urandom, a FIFO), a FIFO as texture, mesh
# and environment map, a decompression bomb as a texture and as an environment (a PNG header declaring 16384², refused from the
# header before decoding); plugin names and paths that are not plugins (GGX, /dev/zero, a
# directory) and an over-long SHADELAB_PLUGIN_PATH; command-line numbers (--size overflowing int,
# --time nan/abc, --accumulate 2abc / 1e9) and --stats to an unwritable path (errno named).
# Also: coordinates beyond float32's useful range (a node at 1e38, an OBJ vertex at 1e38) and a
# node matrix that collapses it (all zero), and shadelab-bench --reference-scale 1000.
# Files a model reader opens itself: a glTF whose buffer or image is a FIFO or a device, an OBJ whose
# mtllib is a FIFO. OBJ through the project's reader: a huge index, a NaN, binary data (each
# "file:line: cause"; test_obj_reader has the rest of the family); a 5000-gon continued over
# lines loads and renders. shadelab-cube (given): special files as IN (/dev/zero,
# a symlink to /dev/random, a FIFO, a directory), procedural specs the core refuses (checker:0, negative
# colours, sky with nan/inf fields) and bad numbers (--size -5, --lod-bias nan, --samples 2abc).
#      usage: hostile_input.sh SHADELAB [SHADELAB-BENCH [SHADELAB-CUBE]]
set -uo pipefail
SL=$(realpath "$1")
BENCH=${2:+$(realpath "$2")}
CUBE=${3:+$(realpath "$3")}
T=$(mktemp -d "${TMPDIR:-/tmp}/shadelab-hostile.XXXXXX")
trap 'rm -rf "$T"' EXIT
cd "$T"
FAILED=0
fail() { echo "FAIL: $*"; FAILED=1; }
mkfifo fifo
printf 'previous output' > keep.png
# 16384x16384 RGB PNG: signature, IHDR, an IDAT of no pixels, IEND (CRCs per the PNG spec's CRC-32)
printf '\x89PNG\r\n\x1a\n\x00\x00\x00\x0dIHDR\x00\x00\x40\x00\x00\x00\x40\x00\x08\x02\x00\x00\x00\x26\xaa\x87\xd3\x00\x00\x00\x08IDAT\x78\x9c\x03\x00\x00\x00\x00\x01\x48\x06\x89\xd2\x00\x00\x00\x00IEND\xae\x42\x60\x82' > bomb.png
sphere='"nodes": [{"name": "a", "mesh": {"primitive": "sphere"}, "material": "m"}], "lights": [{"name": "sun", "type": "directional"}]'
echo "{\"materials\": [{\"name\": \"m\", \"base_color_map\": \"fifo\"}], $sphere}" > tex_fifo.json
echo "{\"materials\": [{\"name\": \"m\", \"base_color_map\": \"bomb.png\"}], $sphere}" > tex_bomb.json
echo "{\"materials\": [{\"name\": \"m\"}], \"nodes\": [{\"name\": \"a\", \"mesh\": {\"file\": \"fifo\"}}]}" > mesh_fifo.json
echo "{\"plugins\": [\"envmap\"], \"environment\": {\"map\": \"fifo\"}, \"materials\": [{\"name\": \"m\"}], $sphere}" > env_fifo.json
echo "{\"plugins\": [\"envmap\"], \"environment\": {\"map\": \"bomb.png\"}, \"materials\": [{\"name\": \"m\"}], $sphere}" > env_bomb.json

# case: expected exit ("fail" = non-zero, "any"), text the message must contain
run() {
  local name=$1 expect=$2 needle=$3; shift 3
  local t0=$SECONDS
  timeout 300 "$SL" --headless --size 32x32 "$@" > "$name.log" 2>&1
  local rc=$?
  printf '%-14s rc=%-3d %2ds  %s\n' "$name" $rc $((SECONDS - t0)) "$(grep -m1 -F -- "$needle" "$name.log" | cut -c1-150)"
  [ $rc -eq 124 ] && { fail "$name: still running after 30 s"; return; }
  [ $rc -ge 126 ] && { fail "$name: crashed or did not start (rc $rc)"; return; }
  [ "$expect" = fail ] && [ $rc -eq 0 ] && fail "$name: exit 0 on bad input"
  grep -qF -- "$needle" "$name.log" || { cat "$name.log"; fail "$name: no message containing '$needle'"; }
}
run scene_zero    fail "/dev/zero: is not a regular file (a device)" --scene /dev/zero --output keep.png
run scene_random  fail "/dev/urandom: is not a regular file (a device)" --scene /dev/urandom --output keep.png
run scene_fifo    fail "fifo: is not a regular file (a FIFO)" --scene fifo --output keep.png
run texture_fifo  any  "tex_fifo.json:1: material 'm' \"base_color_map\": texture fifo: 'fifo' cannot be read" --scene tex_fifo.json --output tex.png
run texture_bomb  any  "image is 16384x16384 (from its header)" --scene tex_bomb.json --output tex.png
run env_bomb      any  "bomb.png: image is 16384x16384 (from its header)" --scene env_bomb.json --output env.png
run mesh_fifo     fail "mesh file 'fifo' cannot be read" --scene mesh_fifo.json --output keep.png
run env_fifo      fail "'fifo' cannot be read" --scene env_fifo.json --output keep.png
run plugin_upper any  'did you mean "ggx"?' --plugin GGX --output p.png
run plugin_device any  "/dev/zero is not a regular file" --plugin /dev/zero --output p.png
run plugin_dir    any  "is a directory, not a plugin file" --plugin "$T/" --output p.png
SHADELAB_PLUGIN_PATH=$(printf '/nonexistent%d:' $(seq 1 20)) run plugin_path any "entries beyond the first" --plugin ggx --output p.png
grep -q "wrote p.png" plugin_path.log || fail "plugin_path: the built-in plugin directory was dropped (ggx not found)"
run cli_size      fail "--size 4294967297x4294967297: expected WxH" --size 4294967297x4294967297 --output keep.png
run cli_time_nan  fail "--time nan: expected seconds" --time nan --output keep.png
run cli_time_abc  fail "--time abc: expected seconds" --time abc --output keep.png
run cli_acc_tail  fail "--accumulate 2abc: expected a whole number 1..1000000" --accumulate 2abc --output keep.png
run cli_acc_huge  fail "--accumulate 1000000000: expected a whole number 1..1000000" --accumulate 1000000000 --output keep.png
run cli_stats     any  "cannot write /proc/x.json: No such file or directory" --stats /proc/x.json --output p.png
echo "{\"environment\": {\"map\": \"bomb.png\"}, \"materials\": [{\"name\": \"m\"}], $sphere}" > env_unused.json
run env_unused    any  "environment map '$T/bomb.png' is not used" --scene env_unused.json --output p.png
cam() { echo "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 2, 5], \"target\": [0, 0, 0], \"near\": $1, \"far\": 100}], \"materials\": [{\"name\": \"m\"}], $sphere}"; }
cam 1e-7 > near_tiny.json
cam 1e-4 > near_small.json
run near_tiny     fail "far/near = 1e+09 is beyond the depth buffer's precision" --scene near_tiny.json --output keep.png
run near_small    any  "far/near = 1e+06 loses depth precision" --scene near_small.json --output p.png
# a truncated JPEG (the first 3000 bytes of one shadelab writes): loaded as recovered, with a warning
"$SL" --headless -q --size 256x256 --output full.jpg && head -c 3000 full.jpg > trunc.jpg
echo "{\"materials\": [{\"name\": \"m\", \"base_color_map\": \"trunc.jpg\"}], $sphere}" > tex_trunc.json
run jpeg_truncated any "trunc.jpg: damaged image data" --scene tex_trunc.json --output p.png
# coordinates and transforms
echo "{\"materials\": [{\"name\": \"m\"}], \"nodes\": [{\"mesh\": {\"primitive\": \"sphere\"}, \"translate\": [1e38, 0, 0]}]}" > far_node.json
echo "{\"materials\": [{\"name\": \"m\"}], \"nodes\": [{\"mesh\": {\"primitive\": \"sphere\"}, \"matrix\": [0,0,0,0, 0,0,0,0, 0,0,0,0, 0,0,0,1]}]}" > zero_matrix.json
printf 'v 0 0 0\nv 1e38 0 0\nv 0 1 0\nf 1 2 3\n' > far.obj
echo "{\"materials\": [{\"name\": \"m\"}], \"nodes\": [{\"mesh\": {\"file\": \"far.obj\"}}]}" > far_mesh.json
run far_node      fail "\"translate\" 1e+38 is beyond 1e+07" --scene far_node.json --output keep.png
run zero_matrix   fail "collapses the node to a line or a point" --scene zero_matrix.json --output keep.png
run far_mesh      fail "reaches 1e+38 from the origin" --scene far_mesh.json --output keep.png
# model files whose parts assimp opens: every open goes through the one regular-file check
buf='"buffers": [{"byteLength": 60, "uri": "BUF"}], "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24}], "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}, {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}]'
gltf() { echo "{\"asset\": {\"version\": \"2.0\"}, \"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"mesh\": 0}], \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0, \"TEXCOORD_0\": 1}, \"material\": 0}]}], \"materials\": [{\"pbrMetallicRoughness\": {\"baseColorTexture\": {\"index\": 0}}}], \"textures\": [{\"source\": 0}], \"images\": [{\"uri\": \"$2\"}], ${buf/BUF/$1}}"; }
b64='data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/'
ln -s /dev/zero zero_link.png
gltf fifo tex.png > buffer_fifo.gltf
gltf "$b64" fifo > image_fifo.gltf
gltf "$b64" zero_link.png > image_device.gltf
printf 'mtllib fifo\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n' > mtl_fifo.obj
run gltf_buffer_fifo fail "fifo: is not a regular file (a FIFO)" --scene buffer_fifo.gltf --output keep.png
run gltf_image_fifo  any  "texture '$T/fifo' (fifo) cannot be read: is not a regular file (a FIFO)" --scene image_fifo.gltf --output p.png
run gltf_image_dev   any  "(zero_link.png) cannot be read: is not a regular file (a device)" --scene image_device.gltf --output p.png
run obj_mtl_fifo     any  "fifo: is not a regular file (a FIFO)" --scene mtl_fifo.obj --output p.png
grep -qF "image_fifo.gltf: material 'image_fifo/material0' (base_color_map): texture" gltf_image_fifo.log || fail "gltf_image_fifo: the texture error does not name the asset and the material"
[ "$(grep -c 'is not a regular file' obj_mtl_fifo.log)" = 1 ] || fail "obj_mtl_fifo: the refusal is not said exactly once"
# OBJ files through the project's own reader (core/scene/obj_reader.c): file:line: cause
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n' > huge_index.obj
printf 'v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n' > nan_vertex.obj
printf 'v 0 0 0\n\x7fELF\x02\x01\x01\x00\x00garbage\n' > binary.obj
# a 5000-gon (fan-triangulated), its face continued over lines with "\", a material from the MTL
awk 'BEGIN { print "mtllib fan.mtl"; for (i = 0; i < 5000; i++) printf "v %.6f %.6f 0\n", cos(6.2831853 * i / 5000), sin(6.2831853 * i / 5000);
             print "usemtl red"; printf "f"; for (i = 1; i <= 5000; i++) printf " %d%s", i, (i % 1000 == 0 && i < 5000) ? " \\\n" : ""; print "" }' > fan.obj
printf 'newmtl red\nKd 1 0 0\n' > fan.mtl
run obj_huge_index   fail "huge_index.obj:4: face: vertex index beyond 2^31" --scene huge_index.obj --output keep.png
run obj_nan_vertex   fail "nan_vertex.obj:2: 'v': nan is not a finite float" --scene nan_vertex.obj --output keep.png
run obj_binary       fail "binary.obj:2: binary data (a NUL byte)" --scene binary.obj --output keep.png
run obj_fan          any  "wrote fan.png" --scene fan.obj --output fan.png
grep -qi "error" obj_fan.log && fail "obj_fan: an error loading a 5000-gon"
if [ -n "$CUBE" ]; then
  printf 'previous output' > keep.exr
  ln -s /dev/random random_link.exr
  mkdir adir
  cube() {
    local name=$1 needle=$2; shift 2
    local t0=$SECONDS
    timeout 300 "$CUBE" "$@" -q > "$name.log" 2>&1
    local rc=$?
    printf '%-14s rc=%-3d %2ds  %s\n' "$name" $rc $((SECONDS - t0)) "$(grep -m1 -F -- "$needle" "$name.log" | cut -c1-150)"
    [ $rc -eq 124 ] && { fail "$name: still running after 20 s"; return; }
    [ $rc -ge 126 ] && { fail "$name: crashed or did not start (rc $rc)"; return; }
    [ $rc -eq 0 ] && fail "$name: exit 0 on bad input"
    grep -qF -- "$needle" "$name.log" || { cat "$name.log"; fail "$name: no message containing '$needle'"; }
  }
  cube cube_zero     "/dev/zero: is not a regular file (a device)" /dev/zero --convert keep.exr --size 8
  cube cube_random   "random_link.exr: is not a regular file (a device)" random_link.exr --convert keep.exr --size 8
  cube cube_fifo     "fifo: is not a regular file (a FIFO)" fifo --ggx keep.exr --size 8
  cube cube_dir      "adir: is a directory" adir --convert keep.exr --size 8
  cube cube_size     "--size -5: expected a whole number 1..8192" sky --ggx keep.exr --size -5
  cube cube_samples  "--samples 2abc: expected a whole number 1..1048576" sky --ggx keep.exr --samples 2abc
  cube cube_bias     "--lod-bias nan: expected a finite number -2..4" sky --ggx keep.exr --lod-bias nan
  cube cube_sky      "ELEVATION (degrees) 'nan' must be a finite number in -90..90" sky:nan:inf:-5 --convert keep.exr --size 8
  cube cube_sky_sun  "SUN_IRRADIANCE (W/m²) '-5' must be a finite number in 0..1000" sky:10:20:-5 --convert keep.exr --size 8
  cube cube_negative "colour '-1,-1,-1' has a component that is negative or not finite" constant:-1,-1,-1 --convert keep.exr --size 8
  cube cube_checker  "N '0' must be a whole number from 1 to the size" checker:0:1,1,1:0,0,0 --convert keep.exr --size 8
  [ "$(cat keep.exr)" = "previous output" ] || fail "shadelab-cube: a failed run overwrote the existing output file"
fi
if [ -n "$BENCH" ]; then
  t0=$SECONDS
  timeout 300 "$BENCH" --plugin core --reference-scale 1000 --out bench_out > bench.log 2>&1; rc=$?
  printf '%-14s rc=%-3d %2ds  %s\n' bench_scale $rc $((SECONDS - t0)) "$(grep -m1 -F -- "--reference-scale 1000" bench.log | cut -c1-150)"
  [ $rc -ne 0 ] && [ $rc -ne 124 ] && grep -qF -- "at most 16384 per side" bench.log || { cat bench.log; fail "bench --reference-scale 1000"; }
fi
[ "$(cat keep.png)" = "previous output" ] || fail "a failed run overwrote the existing output file"
exit $FAILED
