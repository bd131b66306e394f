#!/usr/bin/env bash
# Frame time as the window's user feels it (issue 44): the viewer in its window (GLFW under
# Xvfb), driven by SHADELAB_VIEWER_SCRIPT, turns the camera by a small step every frame for
# FRAMES frames (as a drag does) with the frame-time budget on. The mean time of a motion frame is
# the wall time of that run less the wall time of a run that only opens and quits, divided by
# FRAMES: it includes what the headless --orbit benchmark does not measure (the present scaled up
# to the window, the swap). The two runs alternate ROUNDS times. A benchmark: it prints figures
# and asserts nothing.
#   tools/bench/window-orbit.sh [BUILD_DIR] [SIZE] [FRAMES] [BUDGET_MS] [ROUNDS]
set -euo pipefail
BIN=${1:-build}/shadelab SIZE=${2:-1280x720} FRAMES=${3:-300} BUDGET=${4:-66} ROUNDS=${5:-2}
command -v xvfb-run >/dev/null || { echo "window-orbit.sh: xvfb-run not found (tools/install-deps.sh)" >&2; exit 1; }
orbit=""
for _ in $(seq "$FRAMES"); do orbit="$orbit orbit 0.01 0;"; done
run() { # SCRIPT -> seconds of wall time
    local t0 t1
    t0=$(date +%s.%N)
    SHADELAB_NO_GUI=1 SHADELAB_VIEWER_SCRIPT="$1" timeout 600 xvfb-run -a -s "-screen 0 2000x1200x24" \
        "$BIN" --backend glfw --size "$SIZE" --budget "${BUDGET}ms" >/dev/null 2>&1 ||
        { echo "window-orbit.sh: the viewer failed" >&2; exit 1; }
    t1=$(date +%s.%N)
    awk -v a="$t0" -v b="$t1" 'BEGIN {print b - a}'
}
echo "window orbit: $SIZE, budget $BUDGET ms, $FRAMES motion frames; load: $(cut -d' ' -f1-3 /proc/loadavg)"
for r in $(seq "$ROUNDS"); do
    base=$(run "wait 2; quit")
    moving=$(run "wait 2;$orbit quit")
    awk -v r="$r" -v a="$base" -v b="$moving" -v n="$FRAMES" \
        'BEGIN {ms = (b - a) * 1000 / n; printf "round %d: %.1f ms per motion frame (%.1f frames/s)\n", r, ms, 1000 / ms}'
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
