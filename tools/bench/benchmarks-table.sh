#!/usr/bin/env bash
# Regenerates docs/benchmarks.md: one table of the project's current figures, each with the
# command that measured it, and the date, machine and load average of the run.
#
#   tools/bench/benchmarks-table.sh [BUILD_DIR] [ROUNDS]        (defaults: build, 3)
#
# Environment: SHARED (default ../shared beside the repository: bench/baseline_ggx.c for the
# hand-written floor, assets/ for the head scene; rows that need it are skipped without it),
# OUT (default docs/benchmarks.md; "-" prints to stdout), EXTRAS_BUILD (a build tree of extras/
# searched for many-lights' many_lights_chart besides BUILD_DIR).
# Start-up rows are medians over ROUNDS interleaved rounds with fresh caches ("cold": empty Mesa
# shader cache and shadelab cache) or the same caches again ("warm"). About 3-4 minutes on two
# idle cores. A benchmark: it prints figures and asserts nothing.
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=$(cd "${1:-$ROOT/build}" && pwd) || exit 1
# the figures are the checkout's: bring the build up to date first (a no-op when it is)
cmake --build "$BUILD" -j"$(nproc)" > /dev/null || { echo "benchmarks-table: $BUILD does not build: fix it or pass another build directory" >&2; exit 1; }
ROUNDS=${2:-3}
SHARED=${SHARED:-$ROOT/../shared}
OUT=${OUT:-$ROOT/docs/benchmarks.md}
BIN=$BUILD/shadelab
[ -x "$BIN" ] || { echo "benchmarks-table: no $BIN (build first, or pass the build dir)" >&2; exit 1; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
unset MESA_SHADER_CACHE_DISABLE MESA_GLSL_CACHE_DISABLE
cd "$ROOT" || exit 1

load() { cut -d' ' -f1 /proc/loadavg; }
median() { sort -n | awk '{a[NR] = $1} END {if (!NR) print "-"; else if (NR % 2) print a[(NR + 1) / 2];
                                             else printf "%.3f\n", (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
note() { echo "benchmarks-table: $*" >&2; }
ROWS=()
row() { if [ -n "$3" ]; then ROWS+=("| $1 | $2 | \`$3\` |"); else ROWS+=("| $1 | $2 | the same run |"); fi; }
SKIPPED=()
fresh() { d=$(mktemp -d "$TMP/cache.XXXX"); mkdir -p "$d/mesa"; echo "$d"; }

# start NAME CACHE ARGS...: one headless start to a written PNG; appends "wall cpu first" to
# $TMP/NAME (seconds: the whole process, its user + system time, the viewer's start-up to its
# first complete frame as -v prints it).
start() {
    local name=$1 cache=$2 t first
    shift 2
    if MESA_SHADER_CACHE_DIR=$cache/mesa SHADELAB_CACHE=$cache /usr/bin/time -f "%e %U %S" -o "$TMP/time" \
        "$BIN" --headless --size 1280x720 --frames 1 --output "$TMP/start.png" -v "$@" >/dev/null 2>"$TMP/err"; then
        read -r w u s < "$TMP/time"
        first=$(sed -n 's/.*start-up to the first complete frame: \([0-9.]*\) ms.*/\1/p' "$TMP/err")
        echo "$w $(echo "$u + $s" | bc) $(echo "${first:-0} / 1000" | bc -l)" >> "$TMP/$name"
    else
        note "$name failed: $(tail -2 "$TMP/err")"
    fi
}
# start_row NAME FIGURE COMMAND: the medians of start NAME's runs as a row.
start_row() {
    [ -s "$TMP/$1" ] || return
    local w c f
    w=$(awk '{print $1}' "$TMP/$1" | median) c=$(awk '{print $2}' "$TMP/$1" | median) f=$(awk '{print $3}' "$TMP/$1" | median)
    row "$2" "$(printf '%.2f s first frame, %.2f s to the PNG, %.2f s CPU' "$f" "$w" "$c")" "$3"
}

LOAD0=$(cut -d' ' -f1-3 /proc/loadavg) T0=$(date +%s)
note "start-up, $ROUNDS rounds"
HEAD=tools/bench/startup/head_ibl.json HDR=/usr/share/blender/datafiles/studiolights/world/courtyard.exr
have_head=1
[ -f "$SHARED/assets/head/LeePerrySmith.glb" ] || { have_head=0; SKIPPED+=("the head scene's start (needs \`$SHARED/assets\`)"); }
[ $have_head = 1 ] && [ ! -f "$HDR" ] && { have_head=0; SKIPPED+=("the head scene's start (needs Debian's blender-data)"); }
for r in $(seq "$ROUNDS"); do
    c=$(fresh); start default-cold "$c"; start default-warm "$c"
    start basic-cold "$(fresh)" --scene scenes/basic.json
    if [ $have_head = 1 ]; then
        c=$(fresh); start head-cold "$c" --data "$SHARED/assets" --scene "$HEAD"; start head-warm "$c" --data "$SHARED/assets" --scene "$HEAD"
    fi
done
S="shadelab --headless --size 1280x720 --frames 1 --output F.png -v"
start_row default-cold "built-in default scene, cold start, 1280×720" "$S"
start_row default-warm "built-in default scene, warm start" "$S"
start_row basic-cold "bare scene, cold start" "$S --scene scenes/basic.json"
start_row head-cold "head scene (sss, HDR envmap, tonemap, ggx), cold start" "$S --data DIR --scene $HEAD"
start_row head-warm "head scene, warm start" "$S --data DIR --scene $HEAD"

# frame FIGURE FRAMES ARGS...: shadelab --bench's median frame and forward pass as a row.
frame() {
    local fig=$1 args
    args="--headless --size 1280x720 --frames $2 --bench${3:+ ${*:3}}"
    # shellcheck disable=SC2086
    if "$BIN" $args -q > "$TMP/bench" 2>&1; then
        local fr fw
        fr=$(awk '/frame \(CPU wall\)/ {print $4}' "$TMP/bench") fw=$(awk '$1 == "forward" {print $2}' "$TMP/bench")
        row "$fig" "$(printf '%.1f ms per frame (forward pass %.1f ms)' "$fr" "$fw")" "shadelab $args"
    else
        note "frame $fig failed: $(tail -2 "$TMP/bench")"
    fi
}
note "frame times"
frame "built-in default scene, frame of its still at 1280×720" 12
frame "bare scene, frame at 1280×720" 30 --scene scenes/basic.json

note "supersampling error against time"
metrics="--metric rmse --metric dssim"
"$BUILD/shadelab-bench" --help 2>&1 | grep -qw flip && metrics="$metrics --metric flip"
SSAA="shadelab-bench --plugin core --scene scenes/teapot.json --size 320x180 --reference-scale 2 --vary core.ssaa=1,2,4 --vary core.render_scale=1 --set aa.enabled=false --frames 15 --rounds 3 $metrics"
# shellcheck disable=SC2086
if "$BUILD/shadelab-bench" ${SSAA#shadelab-bench } --no-cache --no-chart --out "$TMP/ssaa" -q > "$TMP/ssaa.log" 2>&1; then
    # by the CSV header's names: label, ok, frame_ms_median, rmse, dssim[, flip, noise]
    awk -F, 'NR == 1 {for (i = 1; i <= NF; i++) col[$i] = i; next}
             $col["ok"] == 1 {gsub(/"/, "", $col["label"]);
                 printf "%s|%.1f ms per frame, RMSE %.4f, DSSIM %.5f", $col["label"], $col["frame_ms_median"], $col["rmse"], $col["dssim"];
                 if ("flip" in col) printf ", FLIP %.4f", $col["flip"];
                 if ("noise" in col && $col["noise"] != "") printf ", noise %.3g", $col["noise"];
                 printf "\n"}' "$TMP/ssaa.csv" > "$TMP/ssaa.rows"
    while IFS='|' read -r label value; do
        row "teapot at 320×180, \`core.$label\` (aa off) against ssaa 8 at 2× size" "$value" "$SSAA"
    done < "$TMP/ssaa.rows"
else
    note "shadelab-bench failed: $(tail -2 "$TMP/ssaa.log")"
fi

note "orbit"
ORBIT="shadelab-bench --orbit 10 --size 320x180"
[ -f "$SHARED/assets/head/LeePerrySmith.glb" ] || SKIPPED+=("the head scene's orbit (needs \`$SHARED/assets\`)")
# shellcheck disable=SC2086
if "$BUILD/shadelab-bench" ${ORBIT#shadelab-bench } --data "$SHARED/assets" --out "$TMP/orbit" -q > "$TMP/orbit.log" 2>&1; then
    python3 - "$TMP/orbit.json" > "$TMP/orbit.rows" <<'PY'
import json, sys
for o in json.load(open(sys.argv[1]))["orbits"]:
    name = "the built-in default scene" if o["scene"].startswith("<") else "`%s`" % o["scene"]
    print("orbit of %s, %dx%d, %.0f s at 10°/s|%d frames: p50 %.0f ms, p95 %.0f, p99 %.0f, %.0f %% over %.0f ms; "
          "FLIP against ssaa 4: motion %.3f, converged still %.3f; flicker %.4f"
          % (name, o["width"], o["height"], o["seconds"], o["frames"], o["p50_ms"], o["p95_ms"], o["p99_ms"],
             100 * o["over_budget"], o["budget_ms"], o["motion_flip"], o["still_flip"], o["flicker"]))
PY
    while IFS='|' read -r label value; do row "$label" "$value" "$ORBIT --data DIR"; done < "$TMP/orbit.rows"
else
    note "shadelab-bench --orbit failed: $(tail -2 "$TMP/orbit.log")"
fi

note "orbit with and without the frame-time budget"
# the truth is the scene's own still at its best settings (--orbit-hq ""): ssaa 4 at this size
# renders 16 times the pixels of each of the still's frames
BORBIT="shadelab-bench --orbit 10 --size 1280x720 --scene scenes/default.json --orbit-points 1 --orbit-hq \"\" --orbit-variant core.budget=66 --orbit-variant core.budget=0 --orbit-rounds 2"
if "$BUILD/shadelab-bench" --orbit 10 --size 1280x720 --scene scenes/default.json --orbit-points 1 --orbit-hq "" \
    --orbit-variant core.budget=66 --orbit-variant core.budget=0 --orbit-rounds 2 --out "$TMP/borbit" -q > "$TMP/borbit.log" 2>&1; then
    python3 - "$TMP/borbit.json" > "$TMP/borbit.rows" <<'PY'
import json, sys
for o in json.load(open(sys.argv[1]))["orbits"]:
    how = "with the frame-time budget (`%s`)" % o["variant"] if o["variant"] != "core.budget=0" else "fixed settings (budget off)"
    print("orbit of the built-in default scene, %dx%d, %s; %d interleaved rounds|%d frames: p50 %.0f ms, p95 %.0f, "
          "p99 %.0f, %.0f %% over %.0f ms; FLIP against the scene's still at its best settings: motion %.3f, "
          "converged still %.3f"
          % (o["width"], o["height"], how, o["rounds"], o["frames"], o["p50_ms"], o["p95_ms"], o["p99_ms"],
             100 * o["over_budget"], o["budget_ms"], o["motion_flip"], o["still_flip"]))
PY
    first=1
    while IFS='|' read -r label value; do
        if [ $first = 1 ]; then row "$label" "$value" "$BORBIT"; first=0; else row "$label" "$value" ""; fi
    done < "$TMP/borbit.rows"
else
    note "shadelab-bench --orbit with the budget failed: $(tail -2 "$TMP/borbit.log")"
fi

note "the hand-written floor"
if [ -f "$SHARED/bench/baseline_ggx.c" ]; then
    # 4 lights: the scene the floor targets are stated for (one GGX sphere, 4 lights, 256²)
    ratio_args=(--sizes 256x256,1280x720 --lights 1,4,64 --rounds "$ROUNDS")
    RATIO="tools/bench/ratio.sh ${ratio_args[*]}"
    if "$ROOT/tools/bench/ratio.sh" --build "$BUILD" --shared "$SHARED" "${ratio_args[@]}" > "$TMP/ratio" 2>&1; then
        # | size | lights | aa | baseline | shadelab | ratio | forward | forward/baseline | TAA share | ...
        awk -F'|' 'NF >= 12 && $3 ~ /[0-9]/ {for (i = 2; i <= 10; i++) gsub(/[* ]/, "", $i);
                   print $2 "|" $3 "|" $4 "|" $5 "|" $6 "|" $7 "|" $9 "|" $10}' "$TMP/ratio" |
        while IFS='|' read -r size n aa b s x f taa; do
            extra=""
            [ "$aa" != off ] && extra=", TAA ${taa/\%/ %} of the frame"
            echo "frame against the hand-written floor, ${size/x/×}, $n of 64 lights, aa $aa|**${x}×** (shadelab $s ms, floor $b ms; forward pass alone **${f}×**$extra)"
        done > "$TMP/ratio.rows"
        first=1
        while IFS='|' read -r fig value; do
            if [ $first = 1 ]; then row "$fig" "$value" "$RATIO"; first=0; else row "$fig" "$value" ""; fi
        done < "$TMP/ratio.rows"
        awk -F'|' 'NF == 7 && $2 ~ /x/ {for (i = 2; i <= 6; i++) gsub(/[* ]/, "", $i); print $2 "|" $3 "|" $6}' "$TMP/ratio" |
        while IFS='|' read -r size aa p; do
            echo "per-light cost against the floor, ${size/x/×}, aa $aa (slope from 1 to 64 lights)|**${p}×**"
        done > "$TMP/slope.rows"
        while IFS='|' read -r fig value; do row "$fig" "$value" ""; done < "$TMP/slope.rows"
    else
        note "ratio.sh failed: $(tail -2 "$TMP/ratio")"
    fi
else
    SKIPPED+=("the hand-written floor (needs \`$SHARED/bench/baseline_ggx.c\`)")
fi

note "many lights"
chart=$(find "$BUILD" ${EXTRAS_BUILD:+"$EXTRAS_BUILD"} -name many_lights_chart -type f -perm -u+x 2>/dev/null | head -1)
if [ -n "$chart" ]; then
    args="--interleave $ROUNDS --size 1280x720 --max-brute 1 --counts 1,1024 --methods brute,tiled,clustered"
    # shellcheck disable=SC2086
    if (cd "$(dirname "$chart")" && "$chart" $args) > "$TMP/ml" 2>&1; then
        x=$(sed -n 's/^1024 lights \/ 1 light.*median \([0-9.]*\)x CPU time.*/\1/p' "$TMP/ml" | head -1)
        [ -n "$x" ] && row "1024 lights against one light, 1280×720, cheapest method" "**${x}×** CPU time" "many_lights_chart $args"
    else
        note "many_lights_chart failed: $(tail -2 "$TMP/ml")"
    fi
else
    SKIPPED+=("many lights (\`many_lights_chart\` is not built; EXTRAS_BUILD names an extras build tree)")
fi

T1=$(date +%s) LOAD1=$(cut -d' ' -f1-3 /proc/loadavg)
RENDERER=$("$BIN" --headless --size 16x16 --frames 1 --output "$TMP/r.png" -v 2>&1 |
           sed -n 's/.*backend \([a-z]*\): \(.*\), OpenGL.*/\1, \2/p' | head -1)
CPU=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)
REV=$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)
{
    echo "# Benchmarks: current figures"
    echo
    fmt -w 100 <<EOF
Generated by \`tools/bench/benchmarks-table.sh ${1:-build} $ROUNDS\` — do not edit by hand; run it
again after a change that moves a figure. Measured $(date -u '+%Y-%m-%d %H:%M UTC') at commit $REV on
$(nproc) cores ($CPU), $RENDERER; load average (1, 5, 15 min) $LOAD0 at the start and $LOAD1 at
the end, $(( (T1 - T0 + 30) / 60 )) min in all. Seconds and milliseconds scale with the machine's
load; ratios measured in one run compare. Start-up rows are medians of $ROUNDS interleaved
round(s); "cold" means an empty Mesa shader cache and shadelab cache, "warm" a second start on them.
EOF
    echo
    echo "| figure | value | measured with |"
    echo "|---|---|---|"
    printf '%s\n' "${ROWS[@]}"
    echo
    if [ ${#SKIPPED[@]} -gt 0 ]; then
        echo "Not measured in this run: $(IFS=';'; echo "${SKIPPED[*]}" | sed 's/;/; /g')."
        echo
    fi
    if [ -f "$ROOT/docs/budget-error.md" ]; then
        echo "Error against the frame-time budget, the budget against fixed render scales on the same orbits:"
        echo "[chart](budget-error.png), [table](budget-error.md) (\`tools/bench/budget-chart.sh\`, its own date and load)."
        echo
    fi
    if [ -f "$ROOT/docs/scale.md" ]; then
        echo "Frame time against the scene's triangles (1 M and 10 M), levels of detail off and on:"
        echo "[chart](scale.png), [table](scale.md) (\`tools/bench/scale-chart.sh\`, its own date and load)."
        echo
    fi
    echo "How \`shadelab-bench\` sweeps quality knobs and computes each metric: [tools/bench](../tools/bench/README.md)."
    echo "Each plugin's own error-versus-time charts are in its README."
} > "$TMP/out.md"
# the cross-check's section (tools/xcheck/xcheck-table.sh regenerates it) is kept as it was
if [ "$OUT" != - ] && [ -f "$OUT" ]; then
    sed -n '/^<!-- xcheck-table begin/,/^<!-- xcheck-table end -->/p' "$OUT" > "$TMP/xcheck.md"
    [ -s "$TMP/xcheck.md" ] && { echo; cat "$TMP/xcheck.md"; } >> "$TMP/out.md"
fi
if [ "$OUT" = - ]; then cat "$TMP/out.md"; else cp "$TMP/out.md" "$OUT" && note "wrote $OUT"; fi
