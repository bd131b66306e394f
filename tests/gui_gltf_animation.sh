#!/usr/bin/env bash
# A glTF animation plays in the window as under --time: Debian's simple_skin (a skin) and
# AnimatedMorphCube (morph target weights), each opened in the viewer under Xvfb (GLFW, Mesa
# llvmpipe GLX), grabbed twice at least 0.5 s of scene time apart (the viewer prints the scene time
# of each grab). Each grab must equal the headless render at that --time (display-encoded PNG,
# max |diff| <= 2/255: measured 2/255 with the pose of the same time, up to 0.4 with another), and
# the two headless renders must differ, so the animation is in effect.
# TAA is off (its history blends the poses of earlier frames) and so is the frame-time budget.
#   usage: gui_gltf_animation.sh SHADELAB IMGDIFF
# Exit 77 (skipped) without xvfb-run or without the models (assimp-testmodels).
set -uo pipefail
SHADELAB=$1 IMGDIFF=$2
M=/usr/share/assimp/models/glTF2
MODELS="$M/simple_skin/simple_skin.gltf $M/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf"
if ! command -v xvfb-run >/dev/null; then
  echo "SKIP: xvfb-run not found: install xvfb and xauth (tools/install-deps.sh)"
  exit 77
fi
for m in $MODELS; do
  [ -f "$m" ] || { echo "SKIP: $m not found (assimp-testmodels, tools/install-deps.sh)"; exit 77; }
done
T=$(mktemp -d "${TMPDIR:-/tmp}/shadelab-gui-anim.XXXXXX")
trap 'rm -rf "$T"' EXIT
FAILED=0
fail() { echo "FAIL: $*"; FAILED=1; }
export SHADELAB_PLUGIN_PATH= SHADELAB_NO_GUI=1
SIZE=160x120
COMMON=(--size $SIZE --budget off --set aa.enabled=false)
for m in $MODELS; do
  n=$(basename "$m" .gltf)
  # b is grabbed one second (wall clock) after a is written
  ( for _ in $(seq 1 1200); do [ -e "$T/$n-a.png" ] && break; sleep 0.1; done; sleep 1; touch "$T/$n-go" ) &
  SHADELAB_VIEWER_SCRIPT="wait 3; grab $T/$n-a.png; waitfile $T/$n-go; grab $T/$n-b.png; quit" \
    timeout 300 xvfb-run -a -s "-screen 0 1280x800x24" "$SHADELAB" --backend glfw "${COMMON[@]}" "$m" 2>"$T/$n.err" >/dev/null
  rc=$?
  wait
  [ $rc -eq 0 ] || { cat "$T/$n.err"; fail "$n: the viewer exited with $rc"; continue; }
  ta=$(sed -n "s|^grabbed the window into $T/$n-a.png (scene time \([^ ]*\) s)$|\1|p" "$T/$n.err")
  tb=$(sed -n "s|^grabbed the window into $T/$n-b.png (scene time \([^ ]*\) s)$|\1|p" "$T/$n.err")
  [ -n "$ta" ] && [ -n "$tb" ] || { cat "$T/$n.err"; fail "$n: no scene time for the grabs"; continue; }
  echo "$n: window grabs at scene times $ta s and $tb s"
  awk -v a="$ta" -v b="$tb" 'BEGIN { exit !(b - a >= 0.5) }' || fail "$n: the window's scene time went from $ta to $tb s"
  for k in a b; do
    t=$ta; [ $k = b ] && t=$tb
    "$SHADELAB" -q --headless "${COMMON[@]}" --time "$t" --output "$T/$n-h$k.png" "$m" || fail "$n: headless at $t s"
    "$IMGDIFF" "$T/$n-$k.png" "$T/$n-h$k.png" --same 0.0080 || fail "$n: the window at $t s is not --time $t"
  done
  "$IMGDIFF" "$T/$n-ha.png" "$T/$n-hb.png" --differ 0.002 || fail "$n: the pose at $ta s is the pose at $tb s"
done
[ $FAILED = 0 ] && echo "PASS: the animations play in the window as under --time"
exit $FAILED
