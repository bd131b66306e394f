#!/usr/bin/env bash
# Frame time against triangle count (issue 44, scale): the built-in default scene, and scenes of
# about 1 M and 10 M triangles made of copies of its teapot and spheres (more finely tessellated)
# in a grid on a wider floor under its camera, sun and spot light, each rendered with levels of
# detail off and on (core.lod_pixels 0 and 1: meshoptimizer's simplifier, chosen by projected
# size), every configuration in turn, ROUNDS times (interleaved). Frustum culling is always on.
# Per configuration: the median frame and forward pass (shadelab --bench) and the triangles drawn
# in the last frame. Writes OUT.csv, OUT.md (the table, with the commands, date, machine, load)
# and OUT.png (gnuplot, log-log). A benchmark: it prints figures and asserts nothing.
#   tools/bench/scale-chart.sh [BUILD_DIR]
# Then one budgeted orbit per scene (shadelab-bench --orbit 10 with core.budget=BUDGET): frame-time
# percentiles, the share over the budget, FLIP of motion and of the converged still.
#   environment: SIZE (1280x720), FRAMES (6), ROUNDS (1), BUDGET (66), OUT (docs/scale)
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=$(cd "${1:-$ROOT/build}" && pwd) || exit 1
SIZE=${SIZE:-1280x720} FRAMES=${FRAMES:-6} ROUNDS=${ROUNDS:-1} BUDGET=${BUDGET:-66} OUT=${OUT:-$ROOT/docs/scale}
BIN=$BUILD/shadelab
[ -x "$BIN" ] || { echo "scale-chart: no $BIN (build first)" >&2; exit 1; }
command -v gnuplot >/dev/null || { echo "scale-chart: gnuplot not found" >&2; exit 1; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
cd "$ROOT" || exit 1

# scenes: GROUPS copies of (a teapot of tessellation 24 and five spheres of 128 x 64), 6 m apart
# on a grid in front of and around the default scene's view
python3 - "$ROOT/scenes/default.json" "$TMP" <<'PY' || exit 1
import json, math, sys
base = json.load(open(sys.argv[1]))
for name, groups in (("1m", 9), ("10m", 85)):
    s = json.loads(json.dumps(base))
    s.pop("gallery", None)
    s["comment"] = "tools/bench/scale-chart.sh: %d copies of the default scene's teapot and spheres" % groups
    side = math.ceil(math.sqrt(groups))
    nodes = [n for n in s["nodes"] if n["name"] == "floor"]
    nodes[0]["mesh"]["size"] = 60 + 6 * side
    teapot = next(n for n in s["nodes"] if n["name"] == "teapot")
    spheres = next(n for n in s["nodes"] if n["name"] == "spheres")["children"]
    for g in range(groups):
        x, z = 6 * (g % side - side // 2), -6 * (g // side)
        t = json.loads(json.dumps(teapot))
        t["name"] = "teapot%d" % g
        t["translate"] = [t["translate"][0] + x, t["translate"][1], t["translate"][2] + z]
        t["mesh"]["tessellation"] = 24
        nodes.append(t)
        for sp in spheres:
            c = json.loads(json.dumps(sp))
            c["name"] = "%s_%d" % (sp["name"], g)
            c["translate"] = [c["translate"][0] + x, c["translate"][1], c["translate"][2] + z]
            c["mesh"]["segments"], c["mesh"]["rings"] = 128, 64
            nodes.append(c)
    s["nodes"] = nodes
    json.dump(s, open("%s/%s.json" % (sys.argv[2], name), "w"), indent=1)
PY

LOAD0=$(cut -d' ' -f1-3 /proc/loadavg) T0=$(date +%s)
: > "$TMP/runs"
for r in $(seq "$ROUNDS"); do
    for scene in default 1m 10m; do
        for lod in 0 1; do
            args=(--headless --size "$SIZE" --frames "$FRAMES" --bench --set "core.lod_pixels=$lod")
            [ "$scene" = default ] || args+=(--scene "$TMP/$scene.json")
            echo "scale-chart: round $r, $scene, core.lod_pixels=$lod" >&2
            if "$BIN" "${args[@]}" -q > "$TMP/bench" 2>&1; then
                fr=$(awk '/frame \(CPU wall\)/ {print $4}' "$TMP/bench") fw=$(awk '$1 == "forward" {print $2}' "$TMP/bench")
                tri=$(sed -n 's/^  triangles: \([0-9]*\) in the scene, \([0-9]*\) drawn.*/\1 \2/p' "$TMP/bench")
                echo "$scene $lod $fr $fw $tri" >> "$TMP/runs"
            else
                echo "scale-chart: $scene lod $lod failed: $(tail -2 "$TMP/bench")" >&2
            fi
        done
    done
done
# the frame-time budget on each scene: a 10 s orbit with core.budget=$BUDGET (levels of detail are
# its last resort: docs/budget.md), frame times from its first frame (the levels' making included)
: > "$TMP/orbits"
for scene in default 1m 10m; do
    args=(--orbit 10 --size "$SIZE" --orbit-points 1 --orbit-hq "" --orbit-variant "core.budget=$BUDGET" --out "$TMP/orbit" -q)
    if [ "$scene" = default ]; then args+=(--scene scenes/default.json); else args+=(--scene "$TMP/$scene.json"); fi
    echo "scale-chart: $scene, orbit with core.budget=$BUDGET" >&2
    if "$BUILD/shadelab-bench" "${args[@]}" > "$TMP/orbit.log" 2>&1; then
        python3 -c 'import json, sys; o = json.load(open(sys.argv[1]))["orbits"][0]
print(sys.argv[2], o["frames"], o["p50_ms"], o["p95_ms"], o["p99_ms"], o["max_ms"], 100 * o["over_budget"], o["motion_flip"], o["still_flip"])' \
            "$TMP/orbit.json" "$scene" >> "$TMP/orbits"
    else
        echo "scale-chart: $scene orbit failed: $(tail -2 "$TMP/orbit.log")" >&2
    fi
done
LOAD1=$(cut -d' ' -f1-3 /proc/loadavg) T1=$(date +%s)

python3 - "$TMP" "$OUT" <<'PY' || exit 1
import statistics, sys
tmp, out = sys.argv[1], sys.argv[2]
scenes = {}
runs = {}
for line in open(tmp + "/runs"):
    sc, lod, fr, fw, total, tri = line.split()
    scenes[sc] = int(total)
    runs.setdefault((sc, lod), []).append((float(fr), float(fw), int(tri)))
rows, dat = [], {"0": [], "1": []}
with open(out + ".csv", "w") as f:
    f.write("scene,scene_triangles,lod_pixels,frame_ms_median,forward_ms_median,triangles_drawn\n")
    for sc in ("default", "1m", "10m"):
        for lod in ("0", "1"):
            if (sc, lod) not in runs: continue
            v = runs[(sc, lod)]
            fr, fw, tri = statistics.median(x[0] for x in v), statistics.median(x[1] for x in v), v[-1][2]
            f.write("%s,%d,%s,%.1f,%.1f,%d\n" % (sc, scenes[sc], lod, fr, fw, tri))
            dat[lod].append("%d %.1f" % (scenes[sc], fr))
            rows.append("| %s | %.2f M | %s | %.0f ms (forward %.0f ms) | %.2f M |" % (
                {"default": "built-in default scene", "1m": "9 copies of its teapot and spheres",
                 "10m": "85 copies of its teapot and spheres"}[sc], scenes[sc] / 1e6,
                "off" if lod == "0" else "1 px", fr, fw, tri / 1e6))
for lod in dat: open("%s/lod%s.dat" % (tmp, lod), "w").write("\n".join(dat[lod]) + "\n")
open(tmp + "/rows", "w").write("\n".join(rows) + "\n")
orbits = []
for line in open(tmp + "/orbits"):
    sc, n, p50, p95, p99, mx, over, fm, fs = line.split()
    orbits.append("| %s | %.2f M | %s | %.0f / %.0f / %.0f ms (largest %.0f) | %.1f %% | %.3f / %.3f |" % (
        {"default": "built-in default scene", "1m": "9 copies", "10m": "85 copies"}[sc], scenes.get(sc, 0) / 1e6, n,
        float(p50), float(p95), float(p99), float(mx), float(over), float(fm), float(fs)))
open(tmp + "/orbit-rows", "w").write("\n".join(orbits) + "\n")
PY

gnuplot <<EOF
set terminal pngcairo size 900,560 font ",11" noenhanced
set output "$OUT.png"
set title "Frame time against the scene's triangles, $SIZE, frustum culling on"
set xlabel "triangles in the scene"
set ylabel "median frame (ms, CPU wall)"
set logscale xy
set grid
set key top left
plot "$TMP/lod0.dat" using 1:2 with linespoints lw 2 pt 7 title "levels of detail off", \
     "$TMP/lod1.dat" using 1:2 with linespoints lw 2 pt 5 title "levels of detail, 1 px (core.lod_pixels=1)"
EOF

CPU=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)
{
    echo "Generated by \`tools/bench/scale-chart.sh\` (per row \`shadelab --headless --size $SIZE --frames $FRAMES --bench"
    echo "--set core.lod_pixels=N [--scene SCENE]\`, $ROUNDS interleaved round(s)) on $(date -u '+%Y-%m-%d %H:%M UTC') at commit"
    echo "$(git rev-parse --short HEAD 2>/dev/null), $(nproc) cores ($CPU), llvmpipe; load average $LOAD0 at the start and"
    echo "$LOAD1 at the end, $(( (T1 - T0 + 30) / 60 )) min. Triangles drawn: the last frame's, every pass (shadow maps too)."
    echo
    echo "| scene | triangles | levels of detail | median frame | triangles drawn |"
    echo "|---|---|---|---|---|"
    cat "$TMP/rows"
    echo
    echo "The frame-time budget on the same scenes: \`shadelab-bench --orbit 10 --size $SIZE --scene SCENE --orbit-points 1"
    echo "--orbit-hq \"\" --orbit-variant core.budget=$BUDGET\` (levels of detail as its last resort: [budget.md](budget.md)). The"
    echo "frame times count every frame of the orbit, the first ones (before the controller has learnt the scene, and"
    echo "the one that makes the levels of detail) too; FLIP against the orbit's own settings' still at the same view."
    echo
    echo "| scene | triangles | frames | frame p50 / p95 / p99 | over $BUDGET ms | FLIP of motion / converged still |"
    echo "|---|---|---|---|---|---|"
    cat "$TMP/orbit-rows"
} > "$OUT.md"
cat "$OUT.md"
echo "scale-chart: wrote $OUT.csv, $OUT.md, $OUT.png" >&2
