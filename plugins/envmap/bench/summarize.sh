#!/usr/bin/env bash
# Joins the four shadelab-bench runs of run.sh with the one-off prefilter cost of each setting
# (measured here with shadelab-cube on the same environment and parameters, best of 2) into
# ibl-summary.csv, and draws ibl-error-vs-ms.png (per-frame cost) and ibl-error-vs-prefilter.png.
# Usage: plugins/envmap/bench/summarize.sh [BUILD_DIR] [DIR]   (DIR holds ibl-r*.csv)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
dir=${2:-$here}
env="checker:12:1.6,1.5,1.3:0.04,0.05,0.07"   # scenes/ibl_bench.json's environment
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefilter_s() { # SIZE SAMPLES LEVELS → seconds (base conversion + GGX chain), best of 2
  local best=""
  for _ in 1 2; do
    t=$("$build/shadelab-cube" "$env" --ggx "$tmp/p.exr" --size "$1" --samples "$2" --levels "$3" -q 2>&1 |
        sed -n 's/.* in \([0-9.]*\) s .*/\1/p')
    if [ -z "$best" ] || awk "BEGIN{exit !($t < $best)}"; then best=$t; fi
  done
  echo "$best"
}
declare -A pre
for s in "samples=512:256 512 9" "samples=16:256 16 9" "samples=64:256 64 9" "samples=128:256 128 9" \
         "samples=1024:256 1024 9" "cube_size=32:32 512 6" "cube_size=64:64 512 7" "cube_size=128:128 512 8" \
         "mip_count=4:256 512 4" "mip_count=6:256 512 6" "lut_size=16:256 512 9"; do
  pre[${s%%:*}]=$(prefilter_s ${s#*:})
done
out=$dir/ibl-summary.csv
echo "roughness,setting,method,rmse,relmse,frame_ms_median,frame_ms_min,forward_ms,prefilter_s" > "$out"
for r in 0.1 0.3 0.6 0.9; do
  tail -n +2 "$dir/ibl-r$r.csv" | while IFS= read -r line; do
    label=$(echo "$line" | cut -d'"' -f4)
    rest=$(echo "$line" | cut -d'"' -f5- | cut -c2-)  # ok,median,mean,min,passes,rmse,relmse,...
    IFS=, read -r ok med mean min passes rmse relmse psnr ssim dssim maxabs nonfin pareto fwd bg disp <<<"$rest"
    case $label in mode=reference*) method=monte-carlo; p=0 ;; *) method=split-sum; p=${pre[$label]:-} ;; esac
    echo "$r,\"${label#mode=reference }\",$method,$rmse,$relmse,$med,$min,$fwd,$p" >> "$out"
  done
done
echo "wrote $out"
plot=""
pt=(5 7 9 11)
i=0
for r in 0.1 0.3 0.6 0.9; do
  plot+="${plot:+, }'< grep -E \"^$r,.*split-sum\" $out' using 7:4 with points pt ${pt[$i]} ps 1.4 lc $((i+1)) title 'split sum, roughness $r'"
  plot+=", '< grep -E \"^$r,.*monte-carlo\" $out' using 7:4 with linespoints pt ${pt[$i]} ps 1.4 dt 2 lc $((i+1)) title 'Monte Carlo 1/4/16 spp, roughness $r'"
  i=$((i+1))
done
gp 900,520 10 "set output '$dir/ibl-error-vs-ms.png'; set datafile separator ','; set logscale xy; set grid;
    set xlabel 'frame time, ms (fastest of 20 frames, 320x180, llvmpipe)'; set ylabel 'RMSE vs reference (8192 spp)';
    set key outside right; set title 'envmap: split sum vs Monte Carlo, per roughness (scenes/ibl_bench.json)'; plot $plot"
plot=""
i=0
for r in 0.1 0.3 0.6 0.9; do
  if [ $r = 0.1 ]; then # labels on one series only, for legibility
    plot+="${plot:+, }'< grep -E \"^$r,.*split-sum\" $out' using 9:4:2 with labels point pt ${pt[$i]} lc $((i+1)) offset 0.5,0.5 font ',8' title 'roughness $r'"
  else
    plot+="${plot:+, }'< grep -E \"^$r,.*split-sum\" $out' using 9:4 with points pt ${pt[$i]} ps 1.4 lc $((i+1)) title 'roughness $r'"
  fi
  i=$((i+1))
done
gp 900,520 10 "set output '$dir/ibl-error-vs-prefilter.png'; set datafile separator ','; set logscale xy; set grid;
    set xlabel 'one-off prefilter time, s (shadelab-cube, llvmpipe)'; set ylabel 'RMSE vs reference (8192 spp)';
    set key outside right; set title 'envmap: split-sum error vs prefilter cost, one knob at a time'; plot $plot"
echo "wrote $dir/ibl-error-vs-ms.png $dir/ibl-error-vs-prefilter.png"
