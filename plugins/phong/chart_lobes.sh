#!/usr/bin/env bash
# blinn-gloss through the lobe contract against the integrators' Monte Carlo references (README
# "Lobes"), with ggx at the same α beside it: runs the two tests that measure it and charts their
# printed figures.
#   envmap      build/tests/test_envmap_lobes: split sum vs envmap's reference (which integrates
#               the model's own f), relative RMS over 3×3 blocks, band environment; coloured
#               (diffuse + specular) and black (the specular lobe alone)
#   area light  test_area_light blinn-gloss / ggx: LTC vs the reference sampling the light,
#               RMSE as a share of the image's peak
# Writes OUT.csv and OUT.png (default plugins/phong/lobes).
#   plugins/phong/chart_lobes.sh [BUILD_DIR] [OUT]
set -euo pipefail
cd "$(dirname "$0")/../.."
B=${1:-build}; OUT=${2:-plugins/phong/lobes}
T=$(mktemp -d "${TMPDIR:-/tmp}/shadelab-lobes.XXXXXX")
trap 'rm -rf "$T"' EXIT
"$B/tests/test_envmap_lobes" >"$T/env.txt" 2>&1 || { cat "$T/env.txt"; echo "test_envmap_lobes failed" >&2; exit 1; }
(cd "$B" && ./extras/area-light/test_area_light blinn-gloss) >"$T/area.txt" 2>&1 ||
  { cat "$T/area.txt"; echo "test_area_light blinn-gloss failed" >&2; exit 1; }
{
  echo "gloss,env_blinn_colour,env_ggx_colour,env_blinn_black,env_ggx_black,area_blinn"
  for g in 0.3 0.5 0.7; do
    pick() { awk -v w="$1" -v g="$g" 'index($0, w) && index($0, "gloss " g) { for (i = 1; i <= NF; i++) if ($i == "rms") print $(i + 1) }' "$T/env.txt" | head -1; }
    area=$(awk -v g="$g" '$1 == "blinn-gloss" && $3 == g":" { for (i = 1; i <= NF; i++) if ($i == "RMSE") { v = $(i + 1); sub("%", "", v); print v / 100 } }' "$T/area.txt")
    echo "$g,$(pick "blinn-gloss colour"),$(pick "ggx         colour"),$(pick "blinn-gloss black"),$(pick "ggx         black"),$area"
  done
} >"$OUT.csv"
cat "$OUT.csv"
gnuplot <<GP
set terminal pngcairo size 760,420 font ",10"
set output "$OUT.png"
set datafile separator ","
set key top left
set xlabel "gloss (blinn-gloss; ggx at the same alpha = sqrt(2/(p+2)), p = 2^(12 gloss))"
set ylabel "error against the Monte Carlo reference"
set xrange [0.25:0.75]
set yrange [0:*]
set xtics 0.2
set grid ytics
set title "blinn-gloss through the lobe contract (one GGX lobe) vs ggx"
plot "$OUT.csv" skip 1 using 1:4 with linespoints lw 2 pt 7 title "envmap, specular only: blinn-gloss", \
     "" skip 1 using 1:5 with linespoints lw 2 pt 5 title "envmap, specular only: ggx", \
     "" skip 1 using 1:2 with linespoints lw 2 pt 7 dt 2 title "envmap, diffuse + specular: blinn-gloss", \
     "" skip 1 using 1:3 with linespoints lw 2 pt 5 dt 2 title "envmap, diffuse + specular: ggx", \
     "" skip 1 using 1:6 with linespoints lw 2 pt 9 title "area light (LTC), RMSE / peak: blinn-gloss"
GP
echo "wrote $OUT.csv and $OUT.png"
