#!/usr/bin/env bash
# What the viewer shows at rest (issue 16's default target): envmap's specular methods as a TAA
# still (the aa plugin on, its default taa_frames jittered frames averaged; fis's sequence continues
# over them, sl_sample_index, ABI 1.9) against the plugin's Monte Carlo reference rendered as the
# same still (taa_frames × 512 spp, the same jitter points), and each still's first frame (what a
# frame in motion shows) against a pixel-centre reference; courtyard.exr (Debian blender-data;
# skipped when absent) and the procedural sky without its sun, metal and dielectric, alpha
# 0.05…1 (bench/ibl_still.c). Then one error-vs-ms chart per alpha with the Pareto front of the
# four spheres' mean (still error), and still-table.md for the README.
# Usage: plugins/envmap/bench/still.sh [BUILD_DIR] [OUT_DIR] [SIZE] [REFERENCE_ACCUMULATE]
#        PLOT_ONLY=1 plugins/envmap/bench/still.sh [BUILD_DIR]   # redraw from still.csv
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
out=${2:-$here}
size=${3:-48}
racc=${4:-8}   # 8 × 64 spp a frame × 16 frames = 8192 spp a pixel, as methods.sh's 128 × 64
envs=(--env sky:0)
hdr=$(blender_hdr "${HDR:-courtyard}")
[ -n "$hdr" ] && envs=(--env "$hdr" --env sky:0)
if [ "${PLOT_ONLY:-0}" != 1 ]; then
  export SHADELAB_CACHE=${SHADELAB_CACHE:-$(mktemp -d)}
  m=(--method "mirror=envmap.specular=mirror" --method "dominant=envmap.specular=dominant")
  for n in 4 8 16 32; do m+=(--method "fis$n=envmap.specular=fis envmap.fis_samples=$n"); done
  for n in 4 8 16 32; do m+=(--method "hybrid$n=envmap.specular=hybrid envmap.fis_samples=$n"); done
  SHADELAB_PLUGIN_PATH="$build/plugins" "$build/plugins/envmap/envmap_bench_still" --size "$size" \
    --reference-accumulate "$racc" "${envs[@]}" "${m[@]}" > "$out/still.csv"
fi
# mean over the spheres per (alpha, method): ms, still error, first-frame error; the Pareto front
awk -F, 'NR > 1 { k = $3 "," $4; ms[k] += $5; e[k] += $6; f[k] += $8; n[k]++ }
  END { for (k in n) print k "," ms[k] / n[k] "," e[k] / n[k] "," f[k] / n[k] }' "$out/still.csv" | sort -t, -k1,1n -k3,3n > "$out/still-mean.csv"
pareto_front "$out/still-mean.csv" > "$out/still-front.csv"
# the README's table: still relative RMS (mean vs the reference's, %) and the first frame's RMS
awk -F, 'NR > 1 { k = $1 "|" $2 "|" $4; v[k "|" $3] = sprintf("%.3f (%+.1f %%) / %.2f", $6, 100 * $7, $8)
                  if (!(($1 "|" $2) in seen)) { seen[$1 "|" $2] = 1; sph[++ns] = $1 "|" $2 } }
  END {
    print "| sphere | method | α = 0.05 | 0.2 | 0.4 | 0.7 | 1.0 |"
    print "|---|---|---|---|---|---|---|"
    nm = split("dominant fis8 fis16 hybrid8 hybrid16", m, " ")
    split("dominant|fis 8|fis 16|hybrid 8|**hybrid 16 (default)**", label, "|")
    na = split("0.05 0.20 0.40 0.70 1.00", a, " ")
    for (s = 1; s <= ns; s++) {
      split(sph[s], p, "|"); name = p[1]; sub(/\.exr$/, "", name); sub(/^sky:0$/, "sky (no sun)", name)
      for (i = 1; i <= nm; i++) {
        line = "| " (i == 1 ? name ", " p[2] : "") " | " label[i]
        for (j = 1; j <= na; j++) line = line " | " v[sph[s] "|" m[i] "|" a[j]]
        print line " |"
      }
    }
  }' "$out/still.csv" > "$out/still-table.md"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmd="set output '$out/still-error-vs-ms.png'; set datafile separator ','; set multiplot layout 2,3 title 'envmap specular methods as a TAA still (aa on, 16 jittered frames) vs the reference rendered as the same still, ${size}x${size}, llvmpipe'; set logscale xy; set grid; set key top right font ',6' samplen 1 spacing 0.8; set xrange [1:100]; set yrange [0.002:20];"
for a in 0.05 0.20 0.40 0.70 1.00; do
  cmd+="set title 'alpha $a'; set xlabel 'ms per frame (fastest of the still)'; set ylabel 'relative RMS';"
  for e in courtyard sky; do for m in metal dielectric; do
    awk -F, -v e="$e" -v m="$m" -v a="$a" 'index($1, e) == 1 && $2 == m && $3 == a' "$out/still.csv" > "$tmp/$e-$m-$a.csv"
  done; done
  cmd+="plot '$tmp/courtyard-metal-$a.csv' using 5:6 with points pt 7 ps 0.8 lc 1 title 'courtyard, metal (still)',"
  cmd+=" '$tmp/courtyard-dielectric-$a.csv' using 5:6 with points pt 5 ps 0.8 lc 2 title 'courtyard, dielectric (still)',"
  cmd+=" '$tmp/sky-metal-$a.csv' using 5:6 with points pt 9 ps 0.8 lc 6 title 'sky, metal (still)',"
  cmd+=" '$tmp/sky-dielectric-$a.csv' using 5:6 with points pt 11 ps 0.8 lc 7 title 'sky, dielectric (still)',"
  cmd+=" '< grep -E \"^$a,\" $out/still-mean.csv' using 3:5 with points pt 6 ps 1 lc 8 title 'mean, first frame (in motion)',"
  cmd+=" '< grep -E \"^$a,\" $out/still-mean.csv' using 3:4:2 with labels point pt 6 ps 1.4 lc 3 offset 0.6,0.5 font ',7' title 'mean of the 4 stills (labelled)',"
  cmd+=" '< grep -E \"^$a,\" $out/still-front.csv' using 3:4 with lines lw 2 lc 4 title 'Pareto front of the still mean',"
  cmd+=" 0.08 with lines dt 2 lc 0 title 'target 0.08';"
done
cmd+="unset multiplot"
gp 1200,760 9 "$cmd"
echo "wrote $out/still.csv, still-mean.csv, still-front.csv, still-table.md, still-error-vs-ms.png"
