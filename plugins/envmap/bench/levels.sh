#!/usr/bin/env bash
# envmap's prefiltered chain (issue 16 item 4): cube size × level count against the Monte Carlo
# reference, relative RMS of a metal sphere per alpha (specular=dominant), on Blender's
# courtyard.exr (Debian blender-data; skipped when absent) and the procedural sky without its sun.
# The roughness-to-level mapping is level m ↔ perceptual roughness m/(count−1) (lod = √α·(count−1)):
# the count decides both the spacing of the roughness levels and the resolution of the roughest
# (level m is a (size/2^m)² mip), so sweeping it measures the mapping's two halves.
# Usage: plugins/envmap/bench/levels.sh [BUILD_DIR] [OUT_DIR] [SIZE] [REFERENCE_FRAMES]
# Writes OUT_DIR/levels.csv (env,material,alpha,term,setting,rel_rms,rel_mean,ratios by n·v) and
# levels.png (rel. RMS vs level count per alpha, one line per cube size and environment).
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
cmd="set output '$out/levels.png'; set datafile separator ','; set multiplot layout 2,3 title 'envmap prefiltered chain: metal sphere rel. RMS vs the reference (${refs}x64 spp), specular=dominant, ${size}x${size}'; set logscale y; set grid; set key top right font ',7'; set xrange [4.5:10.5]; set xlabel 'mip_count (level m = roughness m/(count-1))'; set ylabel 'relative RMS';"
for a in 0.05 0.20 0.40 0.70 1.00; do
  cmd+="set title 'alpha $a'; plot "
  sep=""
  lc=1
  for e in courtyard sky; do for c in 128 256 512; do
    awk -F, -v e="$e" -v c="c$c-" -v a="$a" 'index($1, e) == 1 && $3 == a && index($5, c) == 1 { split($5, p, "-l"); print p[2] "," $6 }' "$out/levels.csv" > "$tmp/$e-$c-$a.csv"
    dt=1; [ $e = sky ] && dt=2
    cmd+="$sep'$tmp/$e-$c-$a.csv' using 1:2 with linespoints dt $dt lc $lc pt 7 title '$e, cube $c'"
    sep=", "
    lc=$((lc + 1))
  done; lc=1; done
  cmd+=";"
done
cmd+="unset multiplot"
gp 1200,700 9 "$cmd"
echo "wrote $out/levels.csv, $out/levels.png"
