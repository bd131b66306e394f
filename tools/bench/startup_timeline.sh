#!/bin/sh
# Where one cold start of the head scene spends its CPU, per 0.1 s (issue 18 item 5):
#
#   tools/bench/startup_timeline.sh [BUILD] [-- extra shadelab options]
#
# Records one cold start (fresh Mesa shader cache and shadelab cache) under `perf record` at
# 2 kHz and prints startup_timeline.py's tables: per time slice, the cores used by llvmpipe's
# rasteriser threads, by the main thread (LLVM apart) and by other threads, and the cores left
# idle; then, where a uprobe on libLLVM's LLVMModuleCreateWithNameInContext can be added (root),
# the LLVM code generation per compiled module (Mesa's fragment, vertex and set-up variants) and
# thread. Needs `perf` (Debian's linux-perf), the data directory (../shared/assets or
# SHADELAB_DATA) and Debian's blender-data, as startup.sh's head rows. A benchmark: it asserts
# nothing; one run is noisy, compare the shape of several.
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
B=${1:-$ROOT/build}
[ $# -gt 0 ] && shift
[ "${1:-}" = "--" ] && shift
DATA=${SHADELAB_DATA:-$ROOT/../shared/assets}
SCENE=$ROOT/tools/bench/startup/head_ibl.json
command -v perf >/dev/null || { echo "startup_timeline.sh: needs perf (apt install linux-perf)" >&2; exit 1; }
[ -x "$B/shadelab" ] || { echo "startup_timeline.sh: no $B/shadelab" >&2; exit 1; }
[ -f "$DATA/head/LeePerrySmith.glb" ] || { echo "startup_timeline.sh: no data directory ($DATA/head)" >&2; exit 1; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
unset MESA_SHADER_CACHE_DISABLE MESA_GLSL_CACHE_DISABLE
mkdir -p "$TMP/cache/mesa"
EVENTS="-e cpu-clock"
LLVM=$(ldconfig -p 2>/dev/null | sed -n 's/.*=> \(.*libLLVM-[0-9]*\.so\.[0-9]*\)$/\1/p' | head -1)
PROBE=probe_libLLVM:LLVMModuleCreateWithNameInContext
if [ -n "$LLVM" ] && { perf probe -l 2>/dev/null | grep -q "$PROBE" ||
    perf probe -q -x "$LLVM" --add 'LLVMModuleCreateWithNameInContext name=+0(%di):string' >/dev/null 2>&1; }; then
    EVENTS="$EVENTS -e $PROBE"
else
    echo "# (no libLLVM uprobe: per-module table left out; run as root for it)"
fi
# shellcheck disable=SC2086
MESA_SHADER_CACHE_DIR=$TMP/cache/mesa SHADELAB_CACHE=$TMP/cache perf record -q -F 2000 $EVENTS -o "$TMP/perf.data" \
    "$B/shadelab" --headless --size 1280x720 --frames 1 --output "$TMP/out.png" -v --data "$DATA" --scene "$SCENE" "$@" \
    2>"$TMP/log" >/dev/null || { echo "startup_timeline.sh: the run failed:" >&2; tail -5 "$TMP/log" >&2; exit 1; }
sed -n 's/.*\(start-up to the first complete frame: .*\)/# \1/p' "$TMP/log"
echo "# load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
perf script -i "$TMP/perf.data" -F comm,tid,time,event,ip,dso,trace 2>/dev/null >"$TMP/script.txt"
python3 "$ROOT/tools/bench/startup_timeline.py" "$TMP/script.txt" 2000 0.1 "$(nproc)"
