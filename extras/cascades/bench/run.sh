#!/usr/bin/env bash
# Error versus time of cascaded shadow maps on scenes/long_floor.json (a 200 m floor, the camera
# 1.7 m above it) with shadelab-bench, against the declared reference: one 8192² map fitted to
# the whole scene (cascades.enabled=false spotlight-shadow.map_size=8192), same PCF 3×3 filter.
# Baseline: one fitted map of the same total memory as each cascade setting (N maps of s² =
# one map of (s·√N)²). always_render=true: every timed frame renders the maps, as a moving
# camera does (a still camera skips the pass).
#   extras/cascades/bench/run.sh [BUILD [OUT_DIR]]
# BUILD: the project's build directory (default build/, as ./build.sh makes it; the extras load by name).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../../../build}" && pwd)
out=${2:-$here}
args=()
for s in 512 1024 2048; do
  for n in 2 3 4; do args+=(--settings "cascades.count=$n spotlight-shadow.map_size=$s"); done
done
for m in 724 887 1024 1448 1774 2048 2896 3547 4096; do
  args+=(--settings "cascades.enabled=false spotlight-shadow.map_size=$m")
done
# CHART_ONLY=1: redraw the chart from an existing long_floor.csv
[ -n "${CHART_ONLY:-}" ] || "$build/shadelab-bench" --plugin cascades --scene "$here/../scenes/long_floor.json" --size 320x180 \
  --set spotlight-shadow.always_render=true --set aa.enabled=false --frames 12 --warmup 3 --rounds 3 \
  --metric rmse --no-cache --no-chart "${args[@]}" --out "$out/long_floor"

# chart: cascades (one line per count) and the equal-memory fitted baseline, the Pareto front joined
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 - "$out" "$tmp" <<'PY'
import csv, sys
out, tmp = sys.argv[1], sys.argv[2]
rows = []
for r in csv.DictReader(open(out + "/long_floor.csv")):
    s = dict(kv.split("=") for kv in r["settings"].split())
    size = int(s["spotlight-shadow.map_size"])
    n = 1 if s.get("cascades.enabled") == "false" else int(s["cascades.count"])
    label = ("fitted %d²" % size) if n == 1 else ("%d × %d²" % (n, size))
    rows.append((label, n, size, float(r["frame_ms_median"]), float(r["rmse"]), float(r["ms_shadow-maps"] or 0)))
front = [r for r in rows if not any(o[3] <= r[3] and o[4] <= r[4] and (o[3] < r[3] or o[4] < r[4]) for o in rows)]
for key, sel in (("fitted", lambda r: r[1] == 1), ("c2", lambda r: r[1] == 2), ("c3", lambda r: r[1] == 3), ("c4", lambda r: r[1] == 4)):
    with open("%s/%s.dat" % (tmp, key), "w") as f:
        for r in sorted(filter(sel, rows), key=lambda r: r[2]): f.write('%.3f %.6f "%s"\n' % (r[3], r[4], r[0]))
with open(tmp + "/front.dat", "w") as f:
    for r in sorted(front, key=lambda r: r[3]): f.write("%.3f %.6f\n" % (r[3], r[4]))
print("%-17s %9s %9s %9s  %s" % ("setting", "frame ms", "shadow ms", "rmse", "front"))
for r in rows: print("%-17s %9.1f %9.1f %9.5f  %s" % (r[0], r[3], r[5], r[4], "*" if r in front else ""))
PY
gnuplot <<GP
set terminal pngcairo noenhanced size 900,560
set output "$out/long_floor.png"
set title "cascades, scenes/long_floor.json (320x180, llvmpipe): RMSE vs one 8192² fitted map"
set xlabel "frame ms (shadelab-bench median; maps rendered every frame)"
set ylabel "RMSE of linear radiance"
set logscale y
set key top right
set grid
plot "$tmp/fitted.dat" using 1:2 with linespoints pt 7 ps 1.3 title "one fitted map (baseline; equal memory: s·√N)", \
     "$tmp/fitted.dat" using 1:2:3 with labels offset 0,-0.9 font ",8" notitle, \
     "$tmp/c2.dat" using 1:2 with linespoints pt 5 ps 1.3 title "2 cascades of s² (s = 512, 1024, 2048)", \
     "$tmp/c3.dat" using 1:2 with linespoints pt 9 ps 1.5 title "3 cascades", \
     "$tmp/c4.dat" using 1:2 with linespoints pt 13 ps 1.5 title "4 cascades", \
     "$tmp/c4.dat" using 1:2:3 with labels offset 0,0.9 font ",8" notitle, \
     "$tmp/front.dat" using 1:2 with lines lc rgb "gray40" title "Pareto front"
GP
echo "wrote $out/long_floor.csv $out/long_floor.png"
