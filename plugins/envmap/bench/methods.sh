#!/usr/bin/env bash
# envmap's specular methods vs its Monte Carlo reference (issue 16): relative RMS per sphere and
# frame time for specular=mirror, dominant, fis N = 1…32 (and fis N = 32 accumulated: its bias),
# on Blender's courtyard.exr (Debian blender-data; skipped when absent; HDR=name picks another) and
# the procedural sky without its sun,
# metal and dielectric, alpha 0.05…1; then one error-vs-ms chart per alpha with the Pareto
# front marked (the front of the mean over the four spheres).
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
# mean over the spheres per (alpha, method), and the Pareto front (no other method both faster and better)
awk -F, 'NR > 1 && $4 != "reference" && $4 != "fis32-accumulated" { k = $3 "," $4; ms[k] += $5; e[k] += $6; n[k]++ }
  END { for (k in n) print k "," ms[k] / n[k] "," e[k] / n[k] }' "$out/methods.csv" | sort -t, -k1,1n -k3,3n > "$out/methods-mean.csv"
pareto_front "$out/methods-mean.csv" > "$out/methods-front.csv"
# the README's table: relative RMS (sphere mean vs the reference's, %) per sphere, method and alpha
awk -F, 'NR > 1 { k = $1 "|" $2 "|" $4; v[k "|" $3] = sprintf("%.3f (%+.1f %%)", $6, 100 * $7)
                  if (!(($1 "|" $2) in seen)) { seen[$1 "|" $2] = 1; sph[++ns] = $1 "|" $2 } }
  END {
    print "| sphere | method | α = 0.05 | 0.2 | 0.4 | 0.7 | 1.0 |"
    print "|---|---|---|---|---|---|---|"
    nm = split("mirror dominant fis8 fis32 hybrid16 fis32-accumulated", m, " ")
    split("mirror|dominant|fis 8|fis 32|**hybrid 16 (default)**, one frame|fis 32 + convolved, accumulated", label, "|")
    na = split("0.05 0.20 0.40 0.70 1.00", a, " ")
    for (s = 1; s <= ns; s++) {
      split(sph[s], p, "|"); name = p[1]; sub(/\.exr$/, "", name); sub(/^sky:0$/, "sky (no sun)", name)
      for (i = 1; i <= nm; i++) {
        line = "| " (i == 1 ? name ", " p[2] : "") " | " label[i]
        for (j = 1; j <= na; j++) line = line " | " v[sph[s] "|" m[i] "|" a[j]]
        print line " |"
      }
    }
  }' "$out/methods.csv" > "$out/methods-table.md"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmd="set output '$out/methods-error-vs-ms.png'; set datafile separator ','; set multiplot layout 2,3 title 'envmap specular methods: relative RMS per sphere vs the Monte Carlo reference (${refs}x64 spp), ${size}x${size}, llvmpipe (frame times: shared 2-core machine under load)'; set logscale xy; set grid; set key bottom left font ',7'; set xrange [1:200]; set yrange [0.003:3];"
for a in 0.05 0.20 0.40 0.70 1.00; do
  cmd+="set title 'alpha $a'; set xlabel 'ms per frame (fastest of 5)'; set ylabel 'relative RMS';"
  for e in courtyard sky; do for m in metal dielectric; do
    awk -F, -v e="$e" -v m="$m" -v a="$a" 'index($1, e) == 1 && $2 == m && $3 == a && $4 != "reference" && $4 !~ /accumulated/' \
      "$out/methods.csv" > "$tmp/$e-$m-$a.csv"
  done; done
  cmd+="plot '$tmp/courtyard-metal-$a.csv' using 5:6 with points pt 7 ps 0.8 lc 1 title 'courtyard, metal',"
  cmd+=" '$tmp/courtyard-dielectric-$a.csv' using 5:6 with points pt 5 ps 0.8 lc 2 title 'courtyard, dielectric',"
  cmd+=" '$tmp/sky-metal-$a.csv' using 5:6 with points pt 9 ps 0.8 lc 6 title 'sky, metal',"
  cmd+=" '$tmp/sky-dielectric-$a.csv' using 5:6 with points pt 11 ps 0.8 lc 7 title 'sky, dielectric',"
  cmd+=" '< grep -E \"^$a,\" $out/methods-mean.csv' using 3:4:2 with labels point pt 6 ps 1.4 lc 3 offset 0.6,0.5 font ',7' title 'mean of the 4 spheres (labelled)',"
  cmd+=" '< grep -E \"^$a,\" $out/methods-front.csv' using 3:4 with lines lw 2 lc 4 title 'Pareto front of the mean',"
  cmd+=" '< grep -E \",$a,fis32-accumulated\" $out/methods.csv' using (150):6 with points pt 3 ps 1.2 lc 8 title 'fis N=32 + irradiance=convolved, accumulated (its bias), at x = 150';"
done
cmd+="unset multiplot"
gp 1200,760 9 "$cmd"
echo "wrote $out/methods.csv, methods-mean.csv, methods-front.csv, methods-table.md, methods-error-vs-ms.png"
