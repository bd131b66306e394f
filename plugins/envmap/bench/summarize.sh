#!/usr/bin/env bash
# Joins the four shadelab-bench runs of run.sh with the one-off prefilter cost of each setting
# (measured here with shadelab-cube on the same environment and parameters, best of 2) into
# ibl-summary.csv, and draws ibl-error-vs-ms.png (per-frame cost) and ibl-error-vs-prefilter.png
# (RMSE), with ibl-flip-vs-ms.png and ibl-flip-vs-prefilter.png beside them (mean FLIP, the same
# points). Noisy settings (the bench's `noisy` column: frames that scatter visibly, tools/bench/
# README.md "Noisy settings") are marked as shadelab-bench marks them, an orange cross, with their
# noise in their label. PLOT_ONLY=1 redraws from an existing ibl-summary.csv.
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
out=$dir/ibl-summary.csv
if [ "${PLOT_ONLY:-0}" != 1 ]; then
declare -A pre
# the levels the plugin builds: mip_count (default 7), at most one fewer than the full chain (envmap.c)
for s in "samples=512:256 512 7" "samples=16:256 16 7" "samples=64:256 64 7" "samples=128:256 128 7" \
         "samples=1024:256 1024 7" "cube_size=32:32 512 5" "cube_size=64:64 512 6" "cube_size=128:128 512 7" \
         "mip_count=4:256 512 4" "mip_count=6:256 512 6" "lut_size=16:256 512 7"; do
  pre[${s%%:*}]=$(prefilter_s ${s#*:})
done
echo "roughness,setting,method,rmse,relmse,frame_ms_median,frame_ms_min,forward_ms,prefilter_s,flip,noise,noisy" > "$out"
for r in 0.1 0.3 0.6 0.9; do
  # shadelab-bench's columns by name (the label is the only quoted field with commas inside: none)
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    { gsub(/"/, ""); print $c["label"] "\t" $c["rmse"] "\t" $c["relmse"] "\t" $c["frame_ms_median"] "\t" $c["frame_ms_min"] "\t" \
        $c["ms_forward"] "\t" $c["flip"] "\t" $c["noise"] "\t" $c["noisy"] }' "$dir/ibl-r$r.csv" |
  while IFS=$'\t' read -r label rmse relmse med min fwd flip noise noisy; do
    case $label in mode=reference*) method=monte-carlo; p=0 ;; *) method=split-sum; p=${pre[$label]:-} ;; esac
    echo "$r,\"${label#mode=reference }\",$method,$rmse,$relmse,$med,$min,$fwd,$p,$flip,$noise,$noisy" >> "$out"
  done
done
fi
echo "wrote $out"
# the noisy rows, and their noise as a label, for the orange crosses (gp_noisy, common.sh)
awk -F, 'NR > 1 && $12 == 1 { printf "%s,noise %.2g\n", $0, $11 }' "$out" > "$tmp/noisy.csv"
noisy=""
[ -s "$tmp/noisy.csv" ] && noisy=", $(gp_noisy "$tmp/noisy.csv" 7 YCOL | sed "s/ title '.*'$/ title 'noisy: its frames scatter visibly'/"), '$tmp/noisy.csv' using 7:YCOL:13 with labels left offset 0.8,0 font ',7' tc rgb '#ff7f0e' notitle"
grep split-sum "$tmp/noisy.csv" > "$tmp/noisy-split.csv" || true
noisy_split=""
[ -s "$tmp/noisy-split.csv" ] && noisy_split=", $(gp_noisy "$tmp/noisy-split.csv" 9 YCOL)"
pt=(5 7 9 11)
lc=(1 2 3 8)   # not 4: orange is the noisy cross
# ms_chart PNG YCOL YLABEL: error vs the fastest frame, per roughness: split sum and Monte Carlo
ms_chart() {
  local plot="" i=0 r
  for r in 0.1 0.3 0.6 0.9; do
    plot+="${plot:+, }'< grep -E \"^$r,.*split-sum\" $out' using 7:$2 with points pt ${pt[$i]} ps 1.4 lc ${lc[$i]} title 'split sum, r $r'"
    plot+=", '< grep -E \"^$r,.*monte-carlo\" $out' using 7:$2 with linespoints pt ${pt[$i]} ps 1.4 dt 2 lc ${lc[$i]} title 'Monte Carlo 1/4/16 spp, r $r'"
    i=$((i+1))
  done
  gp 900,600 10 "set output '$1'; set datafile separator ','; set logscale xy; set grid;
      set xlabel 'frame time, ms (fastest of 20 frames, 320x180, llvmpipe)'; set ylabel '$3';
      set key below maxrows 3 font ',9'; set title 'envmap: split sum vs Monte Carlo, per roughness r (scenes/ibl_bench.json)'; plot $plot${noisy//YCOL/$2}"
}
# the settings' names at roughness 0.1, ordered by prefilter time, in three rows above their
# points (neighbours in time would overlap in one): x, RMSE, FLIP, name, row 0-2
awk -F, '$1 == 0.1 && $3 == "split-sum" { gsub(/"/, "", $2); n = $2
    sub(/^samples=/, "", n); if (n != $2) n = n " samples"; else if (sub(/^cube_size=/, "", n)) n = "cube " n; \
    else if (sub(/^mip_count=/, "", n)) n = n " levels"; else if (sub(/^lut_size=/, "", n)) n = "LUT " n
    if ($2 == "samples=512") n = "base"
    print $9 "," $4 "," $10 "," n }' "$out" | sort -t, -k1,1g | awk '{ print $0 "," (NR - 1) % 3 }' > "$tmp/names.csv"
# prefilter_chart PNG YCOL YLABEL: the split sum's error vs its one-off prefilter time
prefilter_chart() {
  local plot="" i=0 r y=$(( $2 == 4 ? 2 : 3 ))
  for r in 0.1 0.3 0.6 0.9; do
    plot+="${plot:+, }'< grep -E \"^$r,.*split-sum\" $out' using 9:$2 with points pt ${pt[$i]} ps 1.4 lc ${lc[$i]} title 'roughness $r'"
    i=$((i+1))
  done
  plot+=", '$tmp/names.csv' using 1:(\$$y * 1.35**\$5):4 with labels offset 0,0.9 font ',8' notitle"
  gp 900,520 10 "set output '$1'; set datafile separator ','; set logscale xy; set grid;
      set xlabel 'one-off prefilter time, s (shadelab-cube, best of 2, llvmpipe)'; set ylabel '$3';
      set key outside right; set title 'envmap: split-sum error vs prefilter cost, one knob at a time (names: roughness 0.1)'; plot $plot${noisy_split//YCOL/$2}"
}
ms_chart "$dir/ibl-error-vs-ms.png" 4 'RMSE vs reference (8192 spp)'
ms_chart "$dir/ibl-flip-vs-ms.png" 10 'mean FLIP vs reference (8192 spp)'
prefilter_chart "$dir/ibl-error-vs-prefilter.png" 4 'RMSE vs reference (8192 spp)'
prefilter_chart "$dir/ibl-flip-vs-prefilter.png" 10 'mean FLIP vs reference (8192 spp)'
echo "wrote $dir/ibl-error-vs-ms.png $dir/ibl-flip-vs-ms.png $dir/ibl-error-vs-prefilter.png $dir/ibl-flip-vs-prefilter.png"
