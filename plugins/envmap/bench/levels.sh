#!/usr/bin/env bash
# envmap's prefiltered chain (issue 16 item 4): cube size × level count against the Monte Carlo
# reference, relative RMS of a metal sphere per alpha (specular=dominant), on Blender's
# courtyard.exr (Debian blender-data; skipped when absent) and the procedural sky without its sun.
# The roughness-to-level mapping is level m ↔ perceptual roughness m/(count−1) (lod = √α·(count−1)):
# the count decides both the spacing of the roughness levels and the resolution of the roughest
# (level m is a (size/2^m)² mip), so sweeping it measures the mapping's two halves.
# Usage: plugins/envmap/bench/levels.sh [BUILD_DIR] [OUT_DIR] [SIZE] [REFERENCE_FRAMES]
# Writes OUT_DIR/levels.csv (env,material,alpha,term,setting,rel_rms,rel_mean,ratios by n·v,flip,
# noise,noisy: bench/ibl_terms.c), levels.png (rel. RMS vs level count per alpha, one line per cube
# size and environment) and levels-flip.png (FLIP the same way); both titles state the noise of
# the settings' frames (shadelab-bench's measure: the spread of a 16-frame still's samples), the
# largest over the rows, and noisy rows are marked as shadelab-bench marks them.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
out=${2:-$here}
size=${3:-48}
refs=${4:-16}
envs=(--env sky:0)
hdr=$(blender_hdr "${HDR:-courtyard}")
[ -n "$hdr" ] && envs=(--env "$hdr" --env sky:0)
sweep=""
for c in 128 256 512; do
  max=$(awk -v c=$c 'BEGIN { print int(log(c) / log(2) + 1.5) }')
  for l in 5 6 7 8 9 10; do
    [ "$l" -le "$max" ] && sweep+="${sweep:+;}c${c}-l${l}=envmap.cube_size=$c envmap.mip_count=$l"
  done
done
if [ "${PLOT_ONLY:-0}" != 1 ]; then
  export SHADELAB_CACHE=${SHADELAB_CACHE:-$(mktemp -d)}
  SHADELAB_PLUGIN_PATH="$build/plugins" "$build/plugins/envmap/envmap_bench_terms" --size "$size" \
    --reference-frames "$refs" --material metal --sweep "$sweep" "${envs[@]}" > "$out/levels.csv"
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
noise=$(awk -F, 'NR > 1 { if ($12 == "") u = 1; else if ($12 > n) n = $12 }
  END { print u ? "not measured" : n == 0 ? "0 (every sample the same frame)" : sprintf("%.2g", n) }' "$out/levels.csv")
for a in 0.05 0.20 0.40 0.70 1.00; do
  for e in courtyard sky; do for c in 128 256 512; do
    awk -F, -v e="$e" -v c="c$c-" -v a="$a" 'index($1, e) == 1 && $3 == a && index($5, c) == 1 { split($5, p, "-l"); print p[2] "," $6 "," $11 }' "$out/levels.csv" > "$tmp/$e-$c-$a.csv"
  done; done
  awk -F, -v a="$a" '$3 == a && $13 == 1 { split($5, p, "-l"); print p[2] "," $6 "," $11 }' "$out/levels.csv" > "$tmp/noisy-$a.csv"
done
# chart PNG WHAT COLUMN (2: relative RMS, 3: FLIP, of the files above): one panel per alpha, the
# key in the sixth slot
chart() {
  local cmd a e c sep lc dt
  cmd="set output '$1'; set datafile separator ','; set multiplot layout 2,3 title \"envmap prefiltered chain: metal sphere $2 vs the reference (${refs}x64 spp), specular=dominant, ${size}x${size}\nthe noise of the settings' frames (spread of a 16-frame still's samples, the largest over all rows): $noise\"; set logscale y; set grid; unset key; set xrange [4.5:10.5]; set xlabel 'mip_count (level m = roughness m/(count-1))'; set ylabel '$2';"
  for a in 0.05 0.20 0.40 0.70 1.00; do
    t() { [ $a = 1.00 ] && echo "title '$1'" || echo notitle; }
    [ $a = 1.00 ] && cmd+="set key at screen 0.72,0.40 left top Left reverse font ',10' spacing 1.4 samplen 3;"
    cmd+="set title 'alpha $a'; plot "
    sep=""
    lc=1
    for e in courtyard sky; do for c in 128 256 512; do
      dt=1; [ $e = sky ] && dt=2
      cmd+="$sep'$tmp/$e-$c-$a.csv' using 1:$3 with linespoints dt $dt lc $lc pt 7 $(t "$e, cube $c")"
      sep=", "
      lc=$((lc + 1))
    done; lc=1; done
    [ -s "$tmp/noisy-$a.csv" ] && cmd+=", $(gp_noisy "$tmp/noisy-$a.csv" 1 "$3" | sed "s/ title '.*'$/ $(t 'noisy (its frames scatter visibly)')/")"
    cmd+=";"
  done
  cmd+="unset multiplot"
  gp 1200,720 9 "$cmd"
}
chart "$out/levels.png" "relative RMS" 2
chart "$out/levels-flip.png" "mean FLIP" 3
echo "wrote $out/levels.csv, $out/levels.png, $out/levels-flip.png"
