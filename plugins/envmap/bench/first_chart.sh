#!/usr/bin/env bash
# The first frame's error against Cycles (unoccluded reference, bench/cycles.sh on forest,
# courtyard and city) against the forward pass's cost (bench/cost.sh, bench/cost-filtered.csv):
# per method, the worst relative RMS over α = 0.2 / 0.4 / 0.7 / 1 and the three maps, against
# the forward pass in multiples of dominant's in the same round (the mean of the rounds' ratios);
# beside it the worst FLIP over the same spheres and the noise of the method's frames, the noisiest
# of those spheres (cycles.sh's columns: shadelab-xcheck --noise 16, shadelab-bench's measure),
# noisy above SL_NOISE_VISIBLE (tools/bench/include/bench/metrics.h) and marked as shadelab-bench
# marks a noisy setting (tools/bench/README.md, "Noisy settings"). Writes bench/first-vs-cost.csv,
# bench/first-vs-cost.png (relative RMS, the 0.08 target drawn) and bench/first-vs-cost-flip.png.
# Usage: plugins/envmap/bench/first_chart.sh [BUILD_DIR]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
# cost.sh's method spec → cycles.sh's name
name_of() {
  case $1 in
    dominant) echo dominant ;;
    filtered:48) echo filtered ;;
    filtered:48:filtered_lod_bias=0.5*) echo filtered48-before ;;
    filtered:*) echo "filtered${1#filtered:}" ;;
    *) echo "$1" ;;
  esac
}
csv=$here/first-vs-cost.csv
visible=$(awk '$1 == "#define" && $2 == "SL_NOISE_VISIBLE" { print $3 }' "$root/tools/bench/include/bench/metrics.h")
[ -n "$visible" ] || { echo "first_chart.sh: SL_NOISE_VISIBLE not found in tools/bench/include/bench/metrics.h" >&2; exit 1; }
{ echo "method,cost_vs_dominant,worst_rel_rms,forest,courtyard,city,worst_flip,flip_forest,flip_courtyard,flip_city,noise,noisy"
  # the cost file's methods hold commas in their specs: the method is everything between the
  # round and the last three fields
  awk -F, '!/^#/ && NR > 1 { m = $2; for (i = 3; i <= NF - 3; i++) m = m "," $i
      f[$1, m] = $(NF - 2); if (m == "dominant") d[$1] = $(NF - 2); ms[m] = 1; rs[$1] = 1 }
    END { for (m in ms) { s = 0; n = 0; for (r in rs) if ((r, m) in f) { s += f[r, m] / d[r]; n++ }
          printf "%s|%.2f\n", m, s / n } }' "$here/cost-filtered.csv" |
  while IFS='|' read -r spec ratio; do
    name=$(name_of "$spec")
    # worst FILE COLUMN [FORMAT]: the largest value of the method's spheres at alpha >= 0.2
    worst() { awk -F, -v m="$name" -v c="$2" -v fmt="${3:-%.3f}" '$1 == m && $2 != "005" && $c > w { w = $c } END { printf fmt, w }' "$1"; }
    maps=("$here/cycles-unoccluded.csv" "$here/cycles-unoccluded-courtyard.csv" "$here/cycles-unoccluded-city.csv")
    f=$(worst "${maps[0]}" 3) c=$(worst "${maps[1]}" 3) y=$(worst "${maps[2]}" 3)
    ff=$(worst "${maps[0]}" 5) fc=$(worst "${maps[1]}" 5) fy=$(worst "${maps[2]}" 5)
    w=$(printf '%s\n' "$f" "$c" "$y" | sort -g | tail -1)
    wf=$(printf '%s\n' "$ff" "$fc" "$fy" | sort -g | tail -1)
    nz=$(for m in "${maps[@]}"; do worst "$m" 6 '%.5f\n'; done | sort -g | tail -1)
    noisy=$(awk -v n="$nz" -v v="$visible" 'BEGIN { print (n > v) ? 1 : 0 }')
    echo "$name,$ratio,$w,$f,$c,$y,$wf,$ff,$fc,$fy,$nz,$noisy"
  done | sort -t, -k2 -g; } > "$csv"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
awk -F, 'NR > 1 && $12 == 0' "$csv" > "$tmp/quiet.csv"
awk -F, 'NR > 1 && $12 == 1' "$csv" > "$tmp/noisy.csv"
# the label: the method, and its noise when it has any
awk -F, 'NR > 1 { print $0 "," ($11 > 0 ? sprintf("%s (noise %.2g)", $1, $11) : $1) }' "$csv" > "$tmp/labelled.csv"
# chart PNG WHAT WORST_COLUMN FIRST_MAP_COLUMN TARGET PLACES: the worst over the maps and each
# map's, per method; PLACES: "METHOD:DX,DY:left|right ..." where a method's label goes (offset in
# characters from its point; right of it at 1.2,0 unless named) to keep labels off points and lines
chart() {
  local cmd place m pos al
  cmd="set datafile separator ','; set output '$1';
  set title \"envmap first frame vs Cycles (unoccluded): worst $2 at alpha >= 0.2, forest/courtyard/city\nlabels: the noise of the method's frames (the noisiest sphere; the spread of 16 samples of a still)\";
  set xlabel 'forward pass / dominant''s (ibl_spheres 1280x720, llvmpipe)'; set ylabel 'worst $2';
  set key bottom right box opaque; set grid; set yrange [0:*]; set offsets 0, graph 0.3, graph 0.08, 0; set xrange [0:*]; plot "
  [ -n "$5" ] && cmd+="$5 with lines dt 2 lc rgb 'red' title 'target $5',"
  cmd+=" '$tmp/quiet.csv' using 2:$3 with points pt 7 ps 1.5 lc rgb 'blue' title 'all three maps',"
  [ -s "$tmp/noisy.csv" ] && cmd+=" '$tmp/noisy.csv' using 2:$3 with points pt 7 ps 1.5 lc rgb 'blue' notitle, $(gp_noisy "$tmp/noisy.csv" 2 "$3" | sed "s/ title '.*'$/ title 'noisy (its frames scatter visibly)'/"),"
  cmd+=" '$csv' skip 1 using 2:$4 with points pt 2 lc rgb '#33aa77' title 'forest',
       '' skip 1 using 2:$(($4 + 1)) with points pt 4 lc rgb '#aa7733' title 'courtyard',
       '' skip 1 using 2:$(($4 + 2)) with points pt 6 lc rgb '#777777' title 'city'"
  for m in $(awk -F, '{ print $1 }' "$tmp/labelled.csv"); do
    pos=1.2,0 al=left
    for place in $6; do [ "${place%%:*}" = "$m" ] && IFS=: read -r _ pos al <<< "$place"; done
    cmd+=", '$tmp/labelled.csv' using 2:(strcol(1) eq '$m' ? \$$3 : NaN):13 with labels offset $pos $al notitle"
  done
  gp 960,560 12 "$cmd"
}
chart "$here/first-vs-cost.png" "relative RMS" 3 4 0.08 "filtered32:-1.2,0:right filtered:1.2,1.5:left filtered64:1.2,-1.2:left"
chart "$here/first-vs-cost-flip.png" "FLIP" 7 8 "" "filtered32:-1.2,0:right filtered48-before:1.2,0.6:left filtered:-1.2,-1.2:right"
cat "$csv"
echo "$here/first-vs-cost.png $here/first-vs-cost-flip.png" >&2
