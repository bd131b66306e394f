#!/bin/sh
# Interleaved A/B of two builds on the head scene's warm first frame, per phase:
#
#   tools/bench/startup/ab_phases.sh BUILD_A BUILD_B [ROUNDS] [PHASE_REGEX]     (default 3 rounds)
#
# Each build gets its own cache directory (Mesa + shadelab), filled by one unprinted start; then
# per round A then B: `shadelab --headless --size 1280x720 --frames 1 --stats -v` on
# tools/bench/startup/head_ibl.json, printing for the phases matching PHASE_REGEX (default: the
# sss passes, the scene upload, forward and the total) "wall/CPU all threads/CPU main thread" in ms,
# the process's wall and user+system seconds, and the 1-minute load average before the run.
# --stats times every pass with glFinish (what tools/bench/startup.sh measures too). Needs the
# data directory (SHADELAB_DATA or ../shared/assets) and blender-data. A benchmark: asserts nothing.
set -u
ROOT=$(cd "$(dirname "$0")/../../.." && pwd)
A=${1:?build dir A}
B=${2:?build dir B}
ROUNDS=${3:-3}
RE=${4:-'frame 0: sss|frame 0: forward|scene to GL|total'}
DATA=${SHADELAB_DATA:-$ROOT/../shared/assets}
HEAD=$ROOT/tools/bench/startup/head_ibl.json
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
one() { # build cachedir
    MESA_SHADER_CACHE_DIR=$2/mesa SHADELAB_CACHE=$2 /usr/bin/time -f "%e %U %S" -o "$TMP/time" "$1/shadelab" --headless \
        --size 1280x720 --frames 1 --output "$TMP/out.png" --stats "$TMP/stats.json" -q -v --data "$DATA" --scene "$HEAD" 2>&1
}
for b in "$A" "$B"; do
    c=$TMP/cache.$(echo "$b" | md5sum | cut -c1-8); mkdir -p "$c/mesa"; one "$b" "$c" >/dev/null
done
echo "# head scene warm first frame, 1280x720; per phase wall/CPU/main-thread CPU ms; process wall s, user+sys s; load"
for r in $(seq "$ROUNDS"); do
    for b in "$A" "$B"; do
        c=$TMP/cache.$(echo "$b" | md5sum | cut -c1-8); l=$(cut -d' ' -f1 /proc/loadavg)
        phases=$(one "$b" "$c" | grep '^debug:   ' | grep -E "$RE" |
            awk '{n = ""; for (i = 2; i <= NF - 6; i++) n = n (n ? " " : "") $i; printf "%s=%.0f/%.0f/%.0f  ", n, $(NF-5), $(NF-3), $(NF-1)}')
        set -- $(cat "$TMP/time")
        printf '%s  %s| process %ss %ss load %s\n' "$(basename "$b")" "$phases" "$1" "$(echo "$2 + $3" | bc)" "$l"
    done
done
