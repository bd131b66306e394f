#!/bin/sh
# Interleaved A/B of the head scene's start-up between two builds (issue 18 item 5):
#
#   tools/bench/startup_ab.sh BUILD_A BUILD_B [ROUNDS]      (ROUNDS default 8)
#
# Each round runs, for each build, a cold start (fresh Mesa shader cache and shadelab cache) and
# then a warm one on those caches, the two builds' order alternating from round to round; it prints
# the first-frame figure `-v` reports ("start-up to the first complete frame") for each, with the
# 1-minute load average, then the medians, the median of the per-round differences and the number
# of rounds B was faster in. Make BUILD_A from another commit with a worktree:
#   git worktree add /tmp/a REV && (cd /tmp/a && ./build.sh)
# Needs the data directory (../shared/assets or SHADELAB_DATA) and Debian's blender-data, as
# tools/bench/startup.sh's head rows. A benchmark: it prints figures and asserts nothing.
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
A=${1:?usage: startup_ab.sh BUILD_A BUILD_B [ROUNDS]} B=${2:?usage: startup_ab.sh BUILD_A BUILD_B [ROUNDS]}
ROUNDS=${3:-8}
DATA=${SHADELAB_DATA:-$ROOT/../shared/assets}
SCENE=$ROOT/tools/bench/startup/head_ibl.json
for b in "$A" "$B"; do [ -x "$b/shadelab" ] || { echo "startup_ab.sh: no $b/shadelab" >&2; exit 1; }; done
[ -f "$DATA/head/LeePerrySmith.glb" ] || { echo "startup_ab.sh: no data directory ($DATA/head)" >&2; exit 1; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
unset MESA_SHADER_CACHE_DISABLE MESA_GLSL_CACHE_DISABLE

first() { # first BUILD CACHE_DIR: one start, prints its first-frame seconds
    MESA_SHADER_CACHE_DIR=$2/mesa SHADELAB_CACHE=$2 "$1/shadelab" --headless --size 1280x720 --frames 1 \
        --output "$TMP/out.png" -v --data "$DATA" --scene "$SCENE" 2>&1 >/dev/null |
        sed -n 's/.*start-up to the first complete frame: \([0-9.]*\) ms.*/\1/p' | awk '{printf "%.2f", $1 / 1000}'
}
pair() { # pair BUILD: a cold start and a warm one; prints "cold warm"
    c=$(mktemp -d "$TMP/c.XXXX") && mkdir -p "$c/mesa"
    printf '%s %s' "$(first "$1" "$c")" "$(first "$1" "$c")"
    rm -rf "$c"
}
echo "# head scene start-up, 1280x720, first frame in seconds; A = $A, B = $B"
printf '%-6s %8s %8s %8s %8s %6s\n' round A-cold A-warm B-cold B-warm load
for r in $(seq "$ROUNDS"); do
    l=$(cut -d' ' -f1 /proc/loadavg)
    if [ $((r % 2)) = 1 ]; then a=$(pair "$A"); b=$(pair "$B"); else b=$(pair "$B"); a=$(pair "$A"); fi
    printf '%-6s %8s %8s %8s %8s %6s\n' "$r" $a $b "$l" | tee -a "$TMP/rows"
done
median() { sort -n | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
printf '%-6s %8s %8s %8s %8s\n' median "$(awk '{print $2}' "$TMP/rows" | median)" "$(awk '{print $3}' "$TMP/rows" | median)" \
    "$(awk '{print $4}' "$TMP/rows" | median)" "$(awk '{print $5}' "$TMP/rows" | median)"
# paired by round (the machine's speed drifts between rounds more than it does within one): the
# median of A − B and how many rounds B was faster in
for col in cold warm; do
    c=$([ $col = cold ] && echo 2 || echo 3)
    d=$(awk -v c=$c '{printf "%.3f\n", $c - $(c + 2)}' "$TMP/rows" | median)
    n=$(awk -v c=$c '$c > $(c + 2)' "$TMP/rows" | wc -l)
    printf '%s: median of the per-round differences A - B %.2f s; B faster in %d of %d rounds\n' \
        "$col" "$d" "$n" "$(wc -l < "$TMP/rows")"
done
