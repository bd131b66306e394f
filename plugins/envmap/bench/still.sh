#!/usr/bin/env bash
# What the viewer shows at rest (issue 16's default target): envmap's specular methods as a TAA
# still (the aa plugin on, its default taa_frames jittered frames averaged; fis's sequence continues
# over them, sl_sample_index, ABI 1.9) against the plugin's Monte Carlo reference rendered as the
# same still (taa_frames × 512 spp, the same jitter points), and each still's first frame (what a
# frame in motion shows) against a pixel-centre reference; courtyard.exr (Debian blender-data;
# skipped when absent) and the procedural sky without its sun, metal and dielectric, alpha
# 0.05…1 (bench/ibl_still.c), with the still's FLIP and the noise of its frames (shadelab-bench's
# measures, tools/bench/include/bench/metrics.h). Then one error-vs-ms chart per alpha for the
# still's relative RMS (still-error-vs-ms.png) and one for its FLIP (still-flip-vs-ms.png), each
# with the Pareto front of the four spheres' mean, noisy settings marked and left off it as
# shadelab-bench leaves them (tools/bench/README.md, "Noisy settings"), and still-table.md.
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
  for n in 16 32 48; do m+=(--method "filtered$n=envmap.specular=filtered envmap.filtered_samples=$n"); done
  SHADELAB_PLUGIN_PATH="$build/plugins" "$build/plugins/envmap/envmap_bench_still" --size "$size" \
    --reference-accumulate "$racc" "${envs[@]}" "${m[@]}" > "$out/still.csv"
fi
# mean over the spheres per (alpha, method): ms, still error, first-frame error, still FLIP; the
# noise of the noisiest sphere, noisy when any sphere's is (the bench's noisy column), the label
awk -F, 'NR > 1 { k = $3 "," $4; ms[k] += $5; e[k] += $6; f[k] += $8; fl[k] += $10; n[k]++
    if ($11 > nz[k]) nz[k] = $11
    if ($12 == 1) noisy[k] = 1 }
  END { for (k in n) { split(k, p, ","); label = nz[k] > 0 ? sprintf("%s (noise %.2g)", p[2], nz[k]) : p[2]
          printf "%s,%g,%g,%g,%g,%g,%d,%s\n", k, ms[k] / n[k], e[k] / n[k], f[k] / n[k], fl[k] / n[k], nz[k], noisy[k] + 0, label } }' \
  "$out/still.csv" | sort -t, -k1,1n -k3,3n > "$out/still-mean.csv"
# the Pareto fronts of the mean (still relative RMS, still FLIP) among the settings that are not noisy
awk -F, '$8 == 0' "$out/still-mean.csv" > "$out/still-quiet.csv"
pareto_front "$out/still-quiet.csv" 4 > "$out/still-front.csv"
pareto_front "$out/still-quiet.csv" 6 > "$out/still-front-flip.csv"
rm -f "$out/still-quiet.csv"
# the README's tables: still relative RMS (mean vs the reference's, %) / the first frame's RMS, then
# the still's FLIP / the noise of its frames (noisy in bold)
table() {
  awk -F, -v what="$1" 'NR > 1 { k = $1 "|" $2 "|" $4
      if (what == "rms") v[k "|" $3] = sprintf("%.3f (%+.1f %%) / %.2f", $6, 100 * $7, $8)
      else v[k "|" $3] = sprintf("%.3f / %s", $10, $12 == 1 ? sprintf("**%.4f**", $11) : sprintf("%.4f", $11))
      if (!(($1 "|" $2) in seen)) { seen[$1 "|" $2] = 1; sph[++ns] = $1 "|" $2 } }
    END {
      print "| sphere | method | α = 0.05 | 0.2 | 0.4 | 0.7 | 1.0 |"
      print "|---|---|---|---|---|---|---|"
      nm = split("dominant fis8 fis16 hybrid8 hybrid16 filtered16 filtered48", m, " ")
      split("dominant|fis 8|fis 16|hybrid 8|hybrid 16|filtered 16|filtered 48", label, "|")
      na = split("0.05 0.20 0.40 0.70 1.00", a, " ")
      for (s = 1; s <= ns; s++) {
        split(sph[s], p, "|"); name = p[1]; sub(/\.exr$/, "", name); sub(/^sky:0$/, "sky (no sun)", name)
        first = 1
        for (i = 1; i <= nm; i++) {
          if (!((sph[s] "|" m[i] "|" a[1]) in v)) continue
          line = "| " (first ? name ", " p[2] : "") " | " label[i]; first = 0
          for (j = 1; j <= na; j++) line = line " | " v[sph[s] "|" m[i] "|" a[j]]
          print line " |"
        }
      }
    }' "$out/still.csv"
}
{ echo "Relative RMS of the still (its mean against the reference's) / of its first frame:"; echo
  table rms; echo
  echo "FLIP of the still (mean over the sphere's pixels) / noise (RMS spread of the still's frames over them; **noisy**):"; echo
  table flip; } > "$out/still-table.md"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for a in 0.05 0.20 0.40 0.70 1.00; do
  for e in courtyard sky; do for m in metal dielectric; do
    awk -F, -v e="$e" -v m="$m" -v a="$a" 'index($1, e) == 1 && $2 == m && $3 == a' "$out/still.csv" > "$tmp/$e-$m-$a.csv"
  done; done
  grep -E "^$a," "$out/still-mean.csv" > "$tmp/mean-$a.csv" || true
  awk -F, '$8 == 0' "$tmp/mean-$a.csv" > "$tmp/quiet-$a.csv"
  awk -F, '$8 == 1' "$tmp/mean-$a.csv" > "$tmp/noisy-$a.csv"
  for f in front front-flip; do grep -E "^$a," "$out/still-$f.csv" > "$tmp/$f-$a.csv" || true; done
done
# chart PNG YLABEL SPHERE_COLUMN MEAN_COLUMN FRONT YRANGE EXTRA: one panel per alpha; the last one's
# key sits in the sixth slot; EXTRA: more plot elements (with a %a for the alpha)
chart() {
  local cmd a
  cmd="set output '$1'; set datafile separator ','; set multiplot layout 2,3 title \"envmap specular methods as a TAA still (aa on, 16 jittered frames): $2 per sphere vs the reference rendered as the same still, ${size}x${size}, llvmpipe\nlabels: the mean of the 4 spheres and the noise of the noisiest (the spread of the still's frames, sRGB RMS over the sphere)\"; set logscale xy; set grid; unset key; set xrange [1:100]; set yrange [$6];"
  for a in 0.05 0.20 0.40 0.70 1.00; do
    t() { [ $a = 1.00 ] && echo "title '$1'" || echo notitle; }
    [ $a = 1.00 ] && cmd+="set key at screen 0.69,0.40 left top Left reverse font ',9' spacing 1.3 samplen 2;"
    cmd+="set title 'alpha $a'; set xlabel 'ms per frame (fastest of the still)'; set ylabel '$2';"
    cmd+="plot '$tmp/courtyard-metal-$a.csv' using 5:$3 with points pt 7 ps 0.8 lc 1 $(t 'courtyard, metal'),"
    cmd+=" '$tmp/courtyard-dielectric-$a.csv' using 5:$3 with points pt 5 ps 0.8 lc 2 $(t 'courtyard, dielectric'),"
    cmd+=" '$tmp/sky-metal-$a.csv' using 5:$3 with points pt 9 ps 0.8 lc 6 $(t 'sky (no sun), metal'),"
    cmd+=" '$tmp/sky-dielectric-$a.csv' using 5:$3 with points pt 11 ps 0.8 lc 7 $(t 'sky (no sun), dielectric'),"
    [ -n "$7" ] && cmd+=" ${7//%a/$a} $(t 'mean, first frame (in motion)'),"
    cmd+=" '$tmp/quiet-$a.csv' using 3:$4 with points pt 6 ps 1.4 lc 3 $(t 'mean of the 4 stills'),"
    [ -s "$tmp/noisy-$a.csv" ] && cmd+=" $(gp_noisy "$tmp/noisy-$a.csv" 3 "$4" | sed "s/ title '.*'$/ $(t 'noisy (its frames scatter visibly: on no front)')/"),"
    cmd+=" '$tmp/mean-$a.csv' using 3:$4:9 with labels offset 0.6,0.5 left font ',6' notitle,"
    cmd+=" '$tmp/$5-$a.csv' using 3:$4 with linespoints lw 2 pt 7 ps 0.4 lc 4 $(t 'Pareto front of the still mean (not noisy)')"
    [ "$2" = "relative RMS" ] && cmd+=", 0.08 with lines dt 2 lc 0 $(t 'target 0.08')"
    cmd+=";"
  done
  cmd+="unset multiplot"
  gp 1200,800 9 "$cmd"
}
chart "$out/still-error-vs-ms.png" "relative RMS" 6 4 front 0.002:20 "'$tmp/mean-%a.csv' using 3:5 with points pt 6 ps 1 lc 8"
chart "$out/still-flip-vs-ms.png" "still FLIP" 10 6 front-flip 0.002:1 ""
echo "wrote $out/still.csv, still-mean.csv, still-front.csv, still-front-flip.csv, still-table.md, still-error-vs-ms.png, still-flip-vs-ms.png"
