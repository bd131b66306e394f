#!/usr/bin/env bash
# The first frame's error against Cycles (unoccluded reference, bench/cycles.sh on forest,
# courtyard and city) against the forward pass's cost (bench/cost.sh, bench/cost-filtered.csv):
# per method, the worst relative RMS over α = 0.2 / 0.4 / 0.7 / 1 and the three maps, against
# the forward pass in multiples of dominant's in the same round (the mean of the rounds' ratios).
# Writes bench/first-vs-cost.csv and bench/first-vs-cost.png (the 0.08 target drawn).
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
{ echo "method,cost_vs_dominant,worst_rel_rms,forest,courtyard,city"
  # the cost file's methods hold commas in their specs: the method is everything between the
  # round and the last three fields
  awk -F, '!/^#/ && NR > 1 { m = $2; for (i = 3; i <= NF - 3; i++) m = m "," $i
      f[$1, m] = $(NF - 2); if (m == "dominant") d[$1] = $(NF - 2); ms[m] = 1; rs[$1] = 1 }
    END { for (m in ms) { s = 0; n = 0; for (r in rs) if ((r, m) in f) { s += f[r, m] / d[r]; n++ }
          printf "%s|%.2f\n", m, s / n } }' "$here/cost-filtered.csv" |
  while IFS='|' read -r spec ratio; do
    name=$(name_of "$spec")
    worst() { awk -F, -v m="$name" '$1 == m && $2 != "005" && $3 > w { w = $3 } END { printf "%.3f", w }' "$1"; }
    f=$(worst "$here/cycles-unoccluded.csv") c=$(worst "$here/cycles-unoccluded-courtyard.csv") y=$(worst "$here/cycles-unoccluded-city.csv")
    w=$(printf '%s\n' "$f" "$c" "$y" | sort -g | tail -1)
    echo "$name,$ratio,$w,$f,$c,$y"
  done | sort -t, -k2 -g; } > "$csv"
gp 900,520 12 "set datafile separator ','; set output '$here/first-vs-cost.png';
  set title 'envmap first frame vs Cycles (unoccluded): worst relative RMS at alpha >= 0.2, forest/courtyard/city';
  set xlabel 'forward pass / dominant''s (ibl_spheres 1280x720, llvmpipe)'; set ylabel 'worst relative RMS';
  set key top right; set grid; set yrange [0:*]; set xrange [0:*];
  plot 0.08 with lines dt 2 lc rgb 'red' title 'target 0.08',
       '$csv' skip 1 using 2:3 with points pt 7 ps 1.5 lc rgb 'blue' title 'all three maps',
       '' skip 1 using 2:4 with points pt 2 lc rgb '#33aa77' title 'forest',
       '' skip 1 using 2:5 with points pt 4 lc rgb '#aa7733' title 'courtyard',
       '' skip 1 using 2:6 with points pt 6 lc rgb '#777777' title 'city',
       '' skip 1 using 2:(\$3 + (int(\$0) % 2 == 0 ? 0.006 : -0.006)):1 with labels offset 1,0 left notitle"
cat "$csv"
echo "$here/first-vs-cost.png" >&2
