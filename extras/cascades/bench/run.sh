#!/usr/bin/env bash
# Error versus time of cascaded shadow maps on scenes/long_floor.json (a 200 m floor, the camera
# 1.7 m above it) with shadelab-bench, against the declared reference: one 8192² map fitted to
# the whole scene (cascades.enabled=false spotlight-shadow.map_size=8192), same PCF 3×3 filter.
# Baseline: one fitted map of the same total memory as each cascade setting (N maps of s² =
# one map of (s·√N)²). always_render=true: every timed frame renders the maps, as a moving
# camera does (a still camera skips the pass).
#   extras/cascades/bench/run.sh [BUILD [OUT_DIR]]
# BUILD: the project's build directory (default build/, as ./build.sh makes it; the extras load by name).
# Writes OUT_DIR/long_floor.{csv,json}, long_floor.png (RMSE) and long_floor-flip.png (FLIP); the
# table it prints has each setting's noise (spread of a 16-frame still's frames).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../../../build}" && pwd)
out=$(mkdir -p "${2:-$here}" && cd "${2:-$here}" && pwd)
# from the repository's root, so the charts name the scene as extras/… (not this machine's path)
cd "$here/../../.."
echo "load average: $(cut -d" " -f1-3 /proc/loadavg)"
args=()
for s in 512 1024 2048; do
  for n in 2 3 4; do args+=(--settings "cascades.count=$n spotlight-shadow.map_size=$s"); done
done
for m in 724 887 1024 1448 1774 2048 2896 3547 4096; do
  args+=(--settings "cascades.enabled=false spotlight-shadow.map_size=$m")
done
# CHART_ONLY=1: redraw the chart from an existing long_floor.csv
[ -n "${CHART_ONLY:-}" ] || "$build/shadelab-bench" --plugin cascades --scene extras/cascades/scenes/long_floor.json --size 320x180 \
  --set spotlight-shadow.always_render=true --set aa.enabled=false --frames 30 --warmup 3 --rounds 5 \
  --metric rmse --metric flip --no-cache --no-chart "${args[@]}" --out "$out/long_floor"
[ -n "${CHART_ONLY:-}" ] || echo "load average: $(cut -d" " -f1-3 /proc/loadavg)"

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
    rows.append((label, n, size, float(r["frame_ms_median"]), float(r["rmse"]), float(r["ms_shadow-maps"] or 0),
                 float(r["flip"]), float(r["noise"])))
fronts = {}
for m, col in (("rmse", 4), ("flip", 6)):
    fronts[m] = [r for r in rows if not any(o[3] <= r[3] and o[col] <= r[col] and (o[3] < r[3] or o[col] < r[col]) for o in rows)]
    for key, sel in (("fitted", lambda r: r[1] == 1), ("c2", lambda r: r[1] == 2), ("c3", lambda r: r[1] == 3), ("c4", lambda r: r[1] == 4)):
        with open("%s/%s-%s.dat" % (tmp, key, m), "w") as f:
            for r in sorted(filter(sel, rows), key=lambda r: r[2]): f.write('%.3f %.6f "%s"\n' % (r[3], r[col], r[0]))
    with open("%s/front-%s.dat" % (tmp, m), "w") as f:
        for r in sorted(fronts[m], key=lambda r: r[3]): f.write("%.3f %.6f\n" % (r[3], r[col]))
with open(tmp + "/noise.txt", "w") as f:
    top = max(r[7] for r in rows)
    f.write("0 for every setting" if top == 0 else "at most %.3g" % top)
print("%-17s %9s %9s %9s %9s %9s  %s" % ("setting", "frame ms", "shadow ms", "rmse", "flip", "noise", "front rmse/flip"))
for r in rows: print("%-17s %9.1f %9.1f %9.5f %9.5f %9.2g  %s%s" % (r[0], r[3], r[5], r[4], r[6], r[7],
                                                                  "*" if r in fronts["rmse"] else "-", "*" if r in fronts["flip"] else "-"))
PY
noise=$(cat "$tmp/noise.txt")
for m in rmse flip; do
  if [ $m = rmse ]; then png=long_floor.png ylabel="RMSE of linear radiance" what=RMSE
  else png=long_floor-flip.png ylabel="mean FLIP (perceptual, 67 px/degree)" what=FLIP; fi
  gnuplot <<GP
set terminal pngcairo noenhanced size 900,560
set output "$out/$png"
set title "cascades, extras/cascades/scenes/long_floor.json (320x180, llvmpipe): $what vs one 8192² fitted map\nnoise (spread of a 16-frame still's frames): $noise"
set xlabel "frame ms (shadelab-bench median; maps rendered every frame)"
set ylabel "$ylabel"
set logscale y
set key top right
set grid
plot "$tmp/fitted-$m.dat" using 1:2 with linespoints pt 7 ps 1.3 title "one fitted map (baseline; equal memory: s·√N)", \
     "$tmp/fitted-$m.dat" using 1:2:3 with labels offset 0,-0.9 font ",8" notitle, \
     "$tmp/c2-$m.dat" using 1:2 with linespoints pt 5 ps 1.3 title "2 cascades of s² (s = 512, 1024, 2048)", \
     "$tmp/c3-$m.dat" using 1:2 with linespoints pt 9 ps 1.5 title "3 cascades", \
     "$tmp/c4-$m.dat" using 1:2 with linespoints pt 13 ps 1.5 title "4 cascades", \
     "$tmp/c4-$m.dat" using 1:2:3 with labels offset 0,0.9 font ",8" notitle, \
     "$tmp/front-$m.dat" using 1:2 with lines lc rgb "gray40" title "Pareto front"
GP
done
echo "wrote $out/long_floor.csv $out/long_floor.png $out/long_floor-flip.png"
