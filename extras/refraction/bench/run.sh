#!/usr/bin/env bash
# Error versus time of refraction's methods on scenes/sphere.json: time from shadelab-bench (median
# frame ms, every setting interleaved over the rounds in one run), error from
# refraction_sphere_ref against the CPU sphere reference (every internal bounce; tests/sphere_ref.h)
# — not against the plugin's own output. Writes sphere.csv (label, ms, rmse and mean FLIP vs the
# CPU reference, noise from shadelab-bench), sphere.png (RMSE) and sphere-flip.png (FLIP; gnuplot,
# the Pareto front joined). The timed frames are drawn as the error's frame is (aa.enabled=false:
# one frame, no TAA) and run every pass (core.rerun_passes=true: the back-face pass too, as while
# the camera or the object moves; a still renders it once).
#   extras/refraction/bench/run.sh [BUILD [OUT_DIR]]
# BUILD: the project's build directory (default build/, as ./build.sh makes it; the extras load by name).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../../../build}" && pwd)
out=$(mkdir -p "${2:-$here}" && cd "${2:-$here}" && pwd)
# from the repository's root, so the outputs name the scene as extras/… (not this machine's path)
cd "$here/../../.."
echo "load average: $(cut -d" " -f1-3 /proc/loadavg)"
scene=extras/refraction/scenes/sphere.json
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
# CHART_ONLY=1: redraw the charts from the existing bench-timing.csv and bench-error.csv
[ -n "${CHART_ONLY:-}" ] || "$build/shadelab-bench" --plugin refraction --scene "$scene" --size $size --frames 12 --warmup 3 --rounds 5 \
  --set aa.enabled=false --set core.rerun_passes=true --metric rmse --metric flip --no-cache --no-chart "${args[@]}" \
  --out "$out/bench-timing"
eargs=()
for i in "${!sets[@]}"; do eargs+=("${labels[$i]}" "${sets[$i]}"); done
[ -n "${CHART_ONLY:-}" ] || "$build/extras/refraction/refraction_sphere_ref" "$scene" ${size/x/ } "${eargs[@]}" > "$out/bench-error.csv"
echo "load average: $(cut -d" " -f1-3 /proc/loadavg)"

# join: the i-th timing row with the i-th error row (same order); series files for the chart
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 - "$out" "$tmp" <<'PY'
import csv, sys
out, tmp = sys.argv[1], sys.argv[2]
t = list(csv.DictReader(open(out + "/bench-timing.csv")))
e = list(csv.DictReader(open(out + "/bench-error.csv")))
rows = [(ei["label"], float(ti["frame_ms_median"]), float(ei["rmse"]), float(ei["max_abs"]), float(ei["flip"]),
         float(ti["noise"])) for ti, ei in zip(t, e)]
# the fronts over the η = 1.5 settings (the dispersion ones are measured against another reference)
mono = [r for r in rows if not r[0].startswith("dispersion")]
fronts = {col: [r for r in mono if not any(o[1] <= r[1] and o[col] <= r[col] and (o[1] < r[1] or o[col] < r[col]) for o in mono)]
          for col in (2, 4)}
with open(out + "/sphere.csv", "w") as f:
    f.write("label,ms,rmse_vs_sphere_reference,max_abs,flip_vs_sphere_reference,noise,pareto_rmse,pareto_flip\n")
    for r in rows: f.write('"%s",%.3f,%.6f,%.6f,%.6f,%g,%d,%d\n' % (r[0], r[1], r[2], r[3], r[4], r[5], r in fronts[2], r in fronts[4]))
for col, m in ((2, "rmse"), (4, "flip")):
    series = {"single": [], "two": [], "disp": []}
    for r in rows:
        k = "disp" if r[0].startswith("dispersion") else "two" if "two" in r[0] else "single"
        series[k].append(r)
    for k, v in series.items():
        with open("%s/%s-%s.dat" % (tmp, k, m), "w") as f:
            for r in v: f.write('%.3f %.6f "%s"\n' % (r[1], r[col], r[0].replace("two-interface ", "").replace("dispersion ", "")))
    with open("%s/front-%s.dat" % (tmp, m), "w") as f:
        for r in sorted(fronts[col], key=lambda r: r[1]): f.write("%.3f %.6f\n" % (r[1], r[col]))
top = max(r[5] for r in rows)
with open(tmp + "/noise.txt", "w") as f: f.write("0 for every setting" if top == 0 else "at most %.3g" % top)
for r in rows: print("%-40s %8.2f ms  rmse %.5f  max %.4f  flip %.5f  noise %g %s" % (r[0], r[1], r[2], r[3], r[4], r[5],
                                                                                   ("*" if r in fronts[2] else "-") + ("*" if r in fronts[4] else "-")))
PY
noise=$(cat "$tmp/noise.txt")
for m in rmse flip; do
  if [ $m = rmse ]; then png=sphere.png ylabel="RMSE vs the CPU reference"
  else png=sphere-flip.png ylabel="mean FLIP vs the CPU reference (sphere pixels, 67 px/degree)"; fi
  gnuplot <<GP
set terminal pngcairo size 900,560
set output "$out/$png"
set title "refraction, $scene ($size, llvmpipe)\nerror vs the CPU sphere reference (every internal bounce)\nnoise (spread of a 16-frame still's frames, shadelab-bench): $noise"
set xlabel "frame ms (shadelab-bench median, every pass in every frame)"
set ylabel "$ylabel"
set logscale y
set key top right
set grid
plot "$tmp/single-$m.dat" using 1:2 with points pt 7 ps 1.5 title "single interface", \
     "$tmp/two-$m.dat" using 1:2 with points pt 5 ps 1.3 title "two interfaces (steps 0-4)", \
     "$tmp/two-$m.dat" using 1:2:3 with labels offset 0,-0.9 font ",8" notitle, \
     "$tmp/disp-$m.dat" using 1:2 with points pt 9 ps 1.5 title "dispersion η 1.45/1.5/1.58 (on / off)", \
     "$tmp/disp-$m.dat" using 1:2:3 with labels offset 0,0.9 font ",8" notitle, \
     "$tmp/front-$m.dat" using 1:2 with lines lc rgb "gray40" title "Pareto front"
GP
done
echo "wrote $out/sphere.csv $out/sphere.png $out/sphere-flip.png"
