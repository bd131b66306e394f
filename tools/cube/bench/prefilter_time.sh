#!/usr/bin/env bash
# shadelab-cube's prefilter time against cube size (issue 18 item 6, the course's chart):
# --lambertian with each --irradiance method (direct: today's exact sum at every output texel,
# the reference; convolved: the same sum on a 32² grid, resampled; sh: 9 SH coefficients) and
# --ggx (6 levels, 1024 samples), on the procedural sky (1024×512, with its sun); then the error of
# convolved and sh against direct at every size, on the sky and on Blender's courtyard.exr when
# Debian's blender-data is installed. Seconds are the tool's own "in X s" (the whole run: source
# upload, base cube, prefilter, read-back), best of RUNS (default 2).
# Usage: tools/cube/bench/prefilter_time.sh [BUILD_DIR] [OUT_DIR]
#   PLOT_ONLY=1 redraws the chart from OUT_DIR/prefilter-time.csv; TIMES_ONLY=1 skips the error
#   part (its figures do not depend on the load) and keeps irradiance-error.csv.
# Writes OUT_DIR/prefilter-time.csv (mode,size,seconds), irradiance-error.csv
# (env,size,method,rel_rms,max_rel) and prefilter-time.png.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
build=${1:-$root/build}
out=${2:-$here}
runs=${RUNS:-2}
cube="$build/shadelab-cube"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
sizes="16 32 64 128 256 512"
# seconds of one run: the number before " s" in the tool's last line
secs() { "$cube" "$@" -q 2>&1 | sed -n 's/.* in \([0-9.]*\) s.*/\1/p' | tail -1; }
best() { local b=""; for _ in $(seq "$runs"); do local s; s=$(secs "$@"); b=$(awk -v a="$b" -v s="$s" 'BEGIN { print (a == "" || s < a) ? s : a }'); done; echo "$b"; }
# relative RMS and max error of A against B over the cube faces: oiiotool's figures are over the
# whole 4:3 cross, whose 6 of 12 cells are faces (the rest is 0 in both), so RMS_faces/mean_faces
# = RMS·√½/mean and max/mean_faces = max·½/mean
relerr() {
  local mean rms max
  mean=$(oiiotool "$2" --ch R,G,B --printstats 2>/dev/null | awk '/Stats Avg:/ { print ($3 + $4 + $5) / 3; exit }')
  read -r rms max < <(oiiotool "$1" --ch R,G,B "$2" --ch R,G,B --diff 2>/dev/null |
    awk '/RMS error/ { r = $NF } /Max error/ { for (i = 1; i <= NF; i++) if ($i == "=") m = $(i + 1) } END { print r, m }')
  awk -v r="$rms" -v m="$max" -v a="$mean" 'BEGIN { printf "%.5f,%.5f", r * sqrt(0.5) / a, m * 0.5 / a }'
}
if [ "${PLOT_ONLY:-0}" != 1 ]; then
  echo "mode,size,seconds" > "$out/prefilter-time.csv"
  for s in $sizes; do
    for m in convolved sh direct; do
      [ "$m" = direct ] && [ "$s" -gt 256 ] && continue   # 512²: ≈ 1 min a run
      echo "lambertian-$m,$s,$(best sky --lambertian "$tmp/t.exr" --size "$s" --irradiance "$m")" >> "$out/prefilter-time.csv"
    done
    echo "ggx,$s,$(best sky --ggx "$tmp/g.exr" --size "$s")" >> "$out/prefilter-time.csv"
    cat "$out/prefilter-time.csv" | tail -4 >&2
  done
fi
if [ "${PLOT_ONLY:-0}" != 1 ] && [ "${TIMES_ONLY:-0}" != 1 ]; then
  echo "env,size,method,rel_rms,max_rel" > "$out/irradiance-error.csv"
  envs=(sky)
  hdr=$(ls /usr/share/blender/*/datafiles/studiolights/world/courtyard.exr /usr/share/blender/datafiles/studiolights/world/courtyard.exr 2>/dev/null | head -1 || true)
  [ -n "$hdr" ] && envs+=("$hdr")
  for e in "${envs[@]}"; do
    for s in 16 64 256; do
      "$cube" "$e" --lambertian "$tmp/direct.exr" --size "$s" --irradiance direct -q 2>/dev/null
      for m in convolved sh; do
        "$cube" "$e" --lambertian "$tmp/$m.exr" --size "$s" --irradiance "$m" -q 2>/dev/null
        echo "$(basename "$e" .exr),$s,$m,$(relerr "$tmp/$m.exr" "$tmp/direct.exr")" >> "$out/irradiance-error.csv"
      done
    done
  done
fi
gp() { gnuplot -e "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 900,560 font 'sans,10' } else { set terminal png size 900,560 }; set termoption noenhanced; $1"; }
for m in lambertian-direct lambertian-convolved lambertian-sh ggx; do grep "^$m," "$out/prefilter-time.csv" > "$tmp/$m.csv" || true; done
gp "set output '$out/prefilter-time.png'; set datafile separator ','; set title 'shadelab-cube prefilter time vs cube face size (procedural sky 1024x512, llvmpipe, shared 2-core machine)'; set logscale xy; set grid; set key top left; set xlabel 'output face size (texels)'; set ylabel 'seconds (whole run, best of $runs)'; set xtics (16, 32, 64, 128, 256, 512);
plot '$tmp/lambertian-direct.csv' using 2:3 with linespoints pt 7 lw 2 title '--lambertian --irradiance direct (exact sum per texel: O(N^2 x 6·32^2))',
     '$tmp/lambertian-convolved.csv' using 2:3 with linespoints pt 5 lw 2 title '--lambertian (default: convolved on 32^2, resampled)',
     '$tmp/lambertian-sh.csv' using 2:3 with linespoints pt 9 lw 2 title '--lambertian --irradiance sh (9 coefficients)',
     '$tmp/ggx.csv' using 2:3 with linespoints pt 11 lw 2 title '--ggx (6 levels, 1024 samples)'"
echo "wrote $out/prefilter-time.csv, $out/irradiance-error.csv, $out/prefilter-time.png"
