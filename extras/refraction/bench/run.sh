#!/usr/bin/env bash
# Error versus time of refraction's methods on scenes/sphere.json: time from shadelab-bench (median
# frame ms, every setting interleaved over the rounds in one run), error from
# refraction_sphere_ref against the CPU sphere reference (every internal bounce; tests/sphere_ref.h)
# — not against the plugin's own output. Writes sphere.csv (label, ms, rmse vs the CPU reference)
# and sphere.png (gnuplot; the Pareto front joined).
#   extras/refraction/bench/run.sh [BUILD [OUT_DIR]]
# BUILD: the project's build directory (default build/, as ./build.sh makes it; the extras load by name).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../../../build}" && pwd)
out=${2:-$here}
scene=$here/../scenes/sphere.json
size=320x180
D="material.glass.ior_rgb=1.45,1.5,1.58"
labels=() sets=()
add() { labels+=("$1"); sets+=("$2"); }
add "single" "refraction.method=single"
for n in 0 1 2 3 4; do add "two-interface steps=$n" "refraction.method=two-interface refraction.steps=$n"; done
add "dispersion single" "refraction.method=single $D"
add "dispersion off single" "refraction.method=single refraction.dispersion=false $D"
add "dispersion two-interface steps=2" "refraction.method=two-interface refraction.steps=2 $D"
add "dispersion off two-interface steps=2" "refraction.method=two-interface refraction.steps=2 refraction.dispersion=false $D"

args=()
for s in "${sets[@]}"; do args+=(--settings "$s"); done
"$build/shadelab-bench" --plugin refraction --scene "$scene" --size $size --frames 12 --warmup 3 --rounds 5 \
  --metric rmse --no-cache --no-chart "${args[@]}" --out "$out/bench-timing"
eargs=()
for i in "${!sets[@]}"; do eargs+=("${labels[$i]}" "${sets[$i]}"); done
"$build/extras/refraction/refraction_sphere_ref" "$scene" ${size/x/ } "${eargs[@]}" > "$out/bench-error.csv"

# join: the i-th timing row with the i-th error row (same order); series files for the chart
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 - "$out" "$tmp" <<'PY'
import csv, sys
out, tmp = sys.argv[1], sys.argv[2]
t = list(csv.DictReader(open(out + "/bench-timing.csv")))
e = list(csv.DictReader(open(out + "/bench-error.csv")))
rows = [(ei["label"], float(ti["frame_ms_median"]), float(ei["rmse"]), float(ei["max_abs"])) for ti, ei in zip(t, e)]
# the front over the η = 1.5 settings (the dispersion ones are measured against another reference)
mono = [r for r in rows if not r[0].startswith("dispersion")]
front = [r for r in mono if not any(o[1] <= r[1] and o[2] <= r[2] and (o[1] < r[1] or o[2] < r[2]) for o in mono)]
with open(out + "/sphere.csv", "w") as f:
    f.write("label,ms,rmse_vs_sphere_reference,max_abs,pareto\n")
    for r in rows: f.write('"%s",%.3f,%.6f,%.6f,%d\n' % (r[0], r[1], r[2], r[3], r in front))
series = {"single": [], "two": [], "disp": []}
for r in rows:
    k = "disp" if r[0].startswith("dispersion") else "two" if "two" in r[0] else "single"
    series[k].append(r)
for k, v in series.items():
    with open("%s/%s.dat" % (tmp, k), "w") as f:
        for r in v: f.write('%.3f %.6f "%s"\n' % (r[1], r[2], r[0].replace("two-interface ", "").replace("dispersion ", "")))
with open(tmp + "/front.dat", "w") as f:
    for r in sorted(front, key=lambda r: r[1]): f.write("%.3f %.6f\n" % (r[1], r[2]))
for r in rows: print("%-40s %8.2f ms  rmse %.5f  max %.4f %s" % (r[0], r[1], r[2], r[3], "*" if r in front else ""))
PY
gnuplot <<GP
set terminal pngcairo size 900,560
set output "$out/sphere.png"
set title "refraction, scenes/sphere.json ($size, llvmpipe): error vs the CPU sphere reference (all bounces)"
set xlabel "frame ms (shadelab-bench median)"
set ylabel "RMSE vs the CPU reference"
set logscale y
set key top right
set grid
plot "$tmp/single.dat" using 1:2 with points pt 7 ps 1.5 title "single interface", \
     "$tmp/two.dat" using 1:2 with points pt 5 ps 1.3 title "two interfaces (steps 0-4)", \
     "$tmp/two.dat" using 1:2:3 with labels offset 0,-0.9 font ",8" notitle, \
     "$tmp/disp.dat" using 1:2 with points pt 9 ps 1.5 title "dispersion η 1.45/1.5/1.58 (on / off)", \
     "$tmp/disp.dat" using 1:2:3 with labels offset 0,0.9 font ",8" notitle, \
     "$tmp/front.dat" using 1:2 with lines lc rgb "gray40" title "Pareto front"
GP
echo "wrote $out/sphere.csv $out/sphere.png"
