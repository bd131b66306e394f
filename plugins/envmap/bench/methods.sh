#!/usr/bin/env bash
# envmap's specular methods vs its Monte Carlo reference (issue 16): relative RMS per sphere and
# frame time for specular=mirror, dominant, fis N = 1…32 (and fis N = 32 accumulated: its bias),
# on Blender's courtyard.exr (Debian blender-data; skipped when absent; HDR=name picks another) and
# the procedural sky without its sun,
# metal and dielectric, alpha 0.05…1, with FLIP and the noise of each setting's frames
# (shadelab-bench's measures, tools/bench/include/bench/metrics.h: bench/ibl_methods.c); then one
# error-vs-ms chart per alpha for the relative RMS (methods-error-vs-ms.png) and one for FLIP
# (methods-flip-vs-ms.png), each with the Pareto front of the mean over the four spheres, noisy
# settings marked and left off it as shadelab-bench leaves them (tools/bench/README.md, "Noisy
# settings"), and methods-table.md for the README.
# Usage: plugins/envmap/bench/methods.sh [BUILD_DIR] [OUT_DIR] [SIZE] [REFERENCE_FRAMES]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
out=${2:-$here}
size=${3:-48}
refs=${4:-128}  # 128 × 64 spp: at 32 frames the reference's own noise (0.023–0.048 vs the C quadrature on courtyard metal, bench/ibl_rim.c) is the size of the 0.03 target
# courtyard.exr (max/mean radiance ≈ 90) rather than forest.exr (≈ 2000: a sun the reference's
# BRDF sampling needs far more than 2048 spp to resolve per pixel), and the sky without its sun
envs=(--env sky:0)
hdr=$(blender_hdr "${HDR:-courtyard}")
[ -n "$hdr" ] && envs=(--env "$hdr" --env sky:0)
if [ "${PLOT_ONLY:-0}" != 1 ]; then   # PLOT_ONLY=1: redraw from an existing methods.csv
  SHADELAB_PLUGIN_PATH="$build/plugins" "$build/plugins/envmap/envmap_bench_methods" --size "$size" --frames 5 \
    --reference-frames "$refs" "${envs[@]}" > "$out/methods.csv"
fi
# mean over the spheres per (alpha, method): ms, relative RMS, FLIP; the noise of the noisiest
# sphere, noisy when any sphere's is (the bench's noisy column), and the chart's label
awk -F, 'NR > 1 && $4 != "reference" && $4 != "fis32-accumulated" { k = $3 "," $4; ms[k] += $5; e[k] += $6; fl[k] += $8; n[k]++
    if ($9 > nz[k]) nz[k] = $9
    if ($10 == 1) noisy[k] = 1 }
  END { for (k in n) { split(k, p, ","); label = nz[k] > 0 ? sprintf("%s (noise %.2g)", p[2], nz[k]) : p[2]
          printf "%s,%g,%g,%g,%g,%d,%s\n", k, ms[k] / n[k], e[k] / n[k], fl[k] / n[k], nz[k], noisy[k] + 0, label } }' \
  "$out/methods.csv" | sort -t, -k1,1n -k3,3n > "$out/methods-mean.csv"
# the Pareto fronts of the mean (relative RMS, FLIP) among the settings that are not noisy
awk -F, '$7 == 0' "$out/methods-mean.csv" > "$out/methods-quiet.csv"
pareto_front "$out/methods-quiet.csv" 4 > "$out/methods-front.csv"
pareto_front "$out/methods-quiet.csv" 5 > "$out/methods-front-flip.csv"
rm -f "$out/methods-quiet.csv"
# the README's tables: relative RMS (sphere mean vs the reference's, %), then FLIP / noise (noisy
# in bold), per sphere, method and alpha
table() {
  awk -F, -v what="$1" 'NR > 1 { k = $1 "|" $2 "|" $4
      if (what == "rms") v[k "|" $3] = sprintf("%.3f (%+.1f %%)", $6, 100 * $7)
      else v[k "|" $3] = sprintf("%.3f / %s", $8, $9 == "" ? "—" : $10 == 1 ? sprintf("**%.4f**", $9) : sprintf("%.4f", $9))
      if (!(($1 "|" $2) in seen)) { seen[$1 "|" $2] = 1; sph[++ns] = $1 "|" $2 } }
    END {
      print "| sphere | method | α = 0.05 | 0.2 | 0.4 | 0.7 | 1.0 |"
      print "|---|---|---|---|---|---|---|"
      nm = split("mirror dominant fis8 fis32 hybrid16 filtered16 fis32-accumulated", m, " ")
      split("mirror|dominant|fis 8|fis 32|hybrid 16, one frame|filtered 16|fis 32 + convolved, accumulated", label, "|")
      na = split("0.05 0.20 0.40 0.70 1.00", a, " ")
      for (s = 1; s <= ns; s++) {
        split(sph[s], p, "|"); name = p[1]; sub(/\.exr$/, "", name); sub(/^sky:0$/, "sky (no sun)", name)
        for (i = 1; i <= nm; i++) {
          if (!((sph[s] "|" m[i] "|" a[1]) in v)) continue
          line = "| " (i == 1 ? name ", " p[2] : "") " | " label[i]
          for (j = 1; j <= na; j++) line = line " | " v[sph[s] "|" m[i] "|" a[j]]
          print line " |"
        }
      }
    }' "$out/methods.csv"
}
{ echo "Relative RMS per sphere (in brackets: the sphere's mean against the reference's):"; echo
  table rms; echo
  echo "FLIP (mean over the sphere's pixels) / noise (RMS spread of a 16-frame still's frames over them; **noisy**):"; echo
  table flip; } > "$out/methods-table.md"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for a in 0.05 0.20 0.40 0.70 1.00; do
  for e in courtyard sky; do for m in metal dielectric; do
    awk -F, -v e="$e" -v m="$m" -v a="$a" 'index($1, e) == 1 && $2 == m && $3 == a && $4 != "reference" && $4 !~ /accumulated/' \
      "$out/methods.csv" > "$tmp/$e-$m-$a.csv"
  done; done
  grep -E "^$a," "$out/methods-mean.csv" > "$tmp/mean-$a.csv" || true
  awk -F, '$7 == 0' "$tmp/mean-$a.csv" > "$tmp/quiet-$a.csv"
  awk -F, '$7 == 1' "$tmp/mean-$a.csv" > "$tmp/noisy-$a.csv"
  for f in front front-flip; do grep -E "^$a," "$out/methods-$f.csv" > "$tmp/$f-$a.csv" || true; done
done
# chart PNG YLABEL SPHERE_COLUMN MEAN_COLUMN FRONT YRANGE: one panel per alpha; the last one's key
# sits in the sixth slot
chart() {
  local cmd a t
  cmd="set output '$1'; set datafile separator ','; set multiplot layout 2,3 title \"envmap specular methods: $2 per sphere vs the Monte Carlo reference (${refs}x64 spp), ${size}x${size}, one frame, aa off, llvmpipe (frame times: shared 2-core machine)\nlabels: the mean of the 4 spheres and the noise of the noisiest (the spread of a 16-frame still's frames, sRGB RMS over the sphere)\"; set logscale xy; set grid; unset key; set xrange [1:200]; set yrange [$6];"
  for a in 0.05 0.20 0.40 0.70 1.00; do
    t() { [ $a = 1.00 ] && echo "title '$1'" || echo notitle; }
    [ $a = 1.00 ] && cmd+="set key at screen 0.69,0.40 left top Left reverse font ',9' spacing 1.3 samplen 2;"
    cmd+="set title 'alpha $a'; set xlabel 'ms per frame (fastest of 5)'; set ylabel '$2';"
    cmd+="plot '$tmp/courtyard-metal-$a.csv' using 5:$3 with points pt 7 ps 0.8 lc 1 $(t 'courtyard, metal'),"
    cmd+=" '$tmp/courtyard-dielectric-$a.csv' using 5:$3 with points pt 5 ps 0.8 lc 2 $(t 'courtyard, dielectric'),"
    cmd+=" '$tmp/sky-metal-$a.csv' using 5:$3 with points pt 9 ps 0.8 lc 6 $(t 'sky (no sun), metal'),"
    cmd+=" '$tmp/sky-dielectric-$a.csv' using 5:$3 with points pt 11 ps 0.8 lc 7 $(t 'sky (no sun), dielectric'),"
    cmd+=" '$tmp/quiet-$a.csv' using 3:$4 with points pt 6 ps 1.4 lc 3 $(t 'mean of the 4 spheres'),"
    [ -s "$tmp/noisy-$a.csv" ] && cmd+=" $(gp_noisy "$tmp/noisy-$a.csv" 3 "$4" | sed "s/ title '.*'$/ $(t 'noisy (its frames scatter visibly: on no front)')/"),"
    cmd+=" '$tmp/mean-$a.csv' using 3:$4:8 with labels offset 0.6,0.5 left font ',6' notitle,"
    cmd+=" '$tmp/$5-$a.csv' using 3:$4 with linespoints lw 2 pt 7 ps 0.4 lc 4 $(t 'Pareto front of the mean (settings not noisy)'),"
    cmd+=" '< grep -E \",$a,fis32-accumulated\" $out/methods.csv' using (150):$3 with points pt 3 ps 1.2 lc 8 $(t 'fis 32 + convolved, accumulated: its bias (at x = 150)');"
  done
  cmd+="unset multiplot"
  gp 1200,800 9 "$cmd"
}
chart "$out/methods-error-vs-ms.png" "relative RMS" 6 4 front 0.003:3
chart "$out/methods-flip-vs-ms.png" "mean FLIP" 8 5 front-flip 0.003:1
echo "wrote $out/methods.csv, methods-mean.csv, methods-front.csv, methods-front-flip.csv, methods-table.md, methods-error-vs-ms.png, methods-flip-vs-ms.png"
