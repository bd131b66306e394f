#!/usr/bin/env bash
# The window at rest (core/viewer.c, sl_renderer_at_rest) under Xvfb: once the still is complete
# and nothing plays by itself, the viewer waits for events instead of drawing the same image again
# (both cores stayed busy at 8-9 frames a second before); a scene that animates keeps drawing.
# Counts, not times: the viewer's debug lines say when it came to rest and how many of the loop's
# turns drew a frame.
#   usage: gui_rest.sh SHADELAB ANIMATED_SCENE
set -uo pipefail
SHADELAB=$1 ANIMATED=$2
if ! command -v xvfb-run >/dev/null; then
  echo "SKIP: xvfb-run not found: install xvfb and xauth (tools/install-deps.sh) to run the GUI rest test"
  exit 77
fi
T=$(mktemp -d "${TMPDIR:-/tmp}/shadelab-rest.XXXXXX")
trap 'rm -rf "$T"' EXIT
FAILED=0
fail() { echo "FAIL: $*"; FAILED=1; }
run() { # NAME ARGS...: 24 turns of the loop in which the script only waits, then quits
  local name=$1; shift
  SHADELAB_NO_GUI=1 SHADELAB_VIEWER_SCRIPT="wait 24; quit" timeout 600 xvfb-run -a -s "-screen 0 1280x800x24" \
    "$SHADELAB" --backend glfw --size 320x180 -v -v "$@" >"$T/$name.out" 2>"$T/$name.err" || {
    tail -20 "$T/$name.err"; fail "$name: the viewer exited with $?"; }
  grep "viewer:" "$T/$name.err" | sed "s/^/  $name: /"
}
drawn() { sed -n 's/.*viewer: drew \([0-9]*\) frames in \([0-9]*\) turns.*/\1 \2/p' "$T/$1.err"; }

run still
grep -q "viewer: at rest after" "$T/still.err" || fail "the built-in scene's window never came to rest"
read -r d t < <(drawn still)
[ -n "${d:-}" ] && [ "$d" -lt $((t - 10)) ] || fail "the window at rest drew ${d:-?} frames in ${t:-?} turns"

run animated --scene "$ANIMATED"
grep -q "viewer: at rest after" "$T/animated.err" && fail "a scene that animates came to rest"
read -r d t < <(drawn animated)
[ -n "${d:-}" ] && [ "$d" -ge $((t - 1)) ] || fail "the animated scene drew ${d:-?} frames in ${t:-?} turns"
[ $FAILED -eq 0 ] && echo "PASS: the window rests once its still is complete and keeps drawing an animation"
exit $FAILED
