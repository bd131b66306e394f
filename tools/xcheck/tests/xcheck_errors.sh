#!/usr/bin/env bash
# shadelab-xcheck on a glTF whose texture does not decode: shadelab draws its magenta stand-in and
# prints an error, so the tool must exit 2 (the report written, but not a clean measurement), as
# shadelab's own headless run does, never 0. Without Blender: 77 (skipped).
#   usage: xcheck_errors.sh SHADELAB_XCHECK TMPDIR
set -u
XC=$1 TMP=$2
src=/usr/share/assimp/models/glTF2/BoxTextured-glTF
cp "$src/BoxTextured.gltf" "$src/BoxTextured0.bin" "$TMP/" || exit 1
printf '\211PNG\r\n\032\nnot a png' > "$TMP/CesiumLogoFlat.png"
"$XC" --size 32x18 --samples 1 --out "$TMP/out" "$TMP/BoxTextured.gltf" > "$TMP/log" 2>&1
rc=$?
cat "$TMP/log"
[ "$rc" = 77 ] && exit 77
if [ "$rc" != 2 ] || [ ! -f "$TMP/out/report.json" ]; then
    echo "FAIL: exit status $rc, expected 2 with the report written"
    exit 1
fi
echo "exit status 2, the report written: as expected"
