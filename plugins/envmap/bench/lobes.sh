#!/usr/bin/env bash
# The lobe contract's chart: phong's blinn-gloss and ggx lit by envmap's specular=dominant (the
# split sum along the dominant direction, built from each model's lobes: a Blinn-Phong lobe read
# from the Blinn-Phong chain, a GGX lobe from the GGX chain) against envmap's Monte Carlo
# reference, which integrates each model's own f; error over alpha. The specular lobe alone (base
# colour black: the contract's hard part; ggx a glTF dielectric, F0 = 0.04 as blinn-gloss's
# Schlick), blinn-gloss at the power of the same alpha by Walter et al.'s equivalence
# p = 2/alpha^2 - 2 (ggx's `alpha` key sets s.alpha, which blinn-gloss reads). Measured as the lobe
# tests measure (tests/test_envmap_lobes.c): relative RMS of 3 x 3 block means over n.v > 0.2;
# beside it FLIP (per pixel over the same n.v > 0.2, lobes-flip.png) and the noise of the split
# sum's frames (the spread of a 16-frame still's samples, shadelab-bench's measure; stated in both
# titles, its largest over the rows, noisy ones marked as shadelab-bench marks them).
# Under Blender's courtyard.exr and city.exr (Debian blender-data; skipped when absent) and the
# procedural sky without its sun. Runs envmap_bench_methods (bench/ibl_methods.c).
# Usage: plugins/envmap/bench/lobes.sh [BUILD_DIR] [OUT_DIR] [SIZE] [REFERENCE_FRAMES]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
out=${2:-$here}
size=${3:-32}
refs=${4:-64}
alphas=${ALPHAS:-0.05,0.1,0.2,0.3,0.4,0.6,0.8}
envs=()
for name in courtyard city; do
  hdr=$(blender_hdr "$name")
  [ -n "$hdr" ] && envs+=(--env "$hdr")
done
envs+=(--env sky:0)
if [ "${PLOT_ONLY:-0}" != 1 ]; then   # PLOT_ONLY=1: redraw from an existing lobes.csv
  SHADELAB_PLUGIN_PATH="$build/plugins" "$build/plugins/envmap/envmap_bench_methods" --size "$size" --frames 1 \
    --reference-frames "$refs" "${envs[@]}" --no-accumulated --alphas "$alphas" --min-nv 0.2 --blocks \
    --method split-sum="envmap.specular=dominant" \
    --plugin ggx --plugin phong \
    --material blinn-gloss='"model": "blinn-gloss", "base_color": [0, 0, 0]' \
    --material ggx='"model": "ggx", "fresnel": "metallic-roughness", "metallic": 0, "base_color": [0, 0, 0]' \
    > "$out/lobes.csv"
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for e in courtyard city sky; do for m in blinn-gloss ggx; do
  awk -F, -v e="$e" -v m="$m" 'index($1, e) == 1 && $2 == m && $4 == "split-sum"' "$out/lobes.csv" > "$tmp/$e-$m.csv"
done; done
# the split sum's noise: the largest over the rows (measured for every row: empty = not measured)
noise=$(awk -F, 'NR > 1 && $4 == "split-sum" { if ($9 == "") u = 1; else if ($9 > n) n = $9 }
  END { print u ? "not measured" : n == 0 ? "0 (every sample the same frame)" : sprintf("%.2g", n) }' "$out/lobes.csv")
awk -F, 'NR > 1 && $4 == "split-sum" && $10 == 1' "$out/lobes.csv" > "$tmp/noisy.csv"
# chart PNG WHAT COLUMN MEASURED_ON
chart() {
  local cmd plot e dt pb pg label
  cmd="set output '$1'; set datafile separator ',';"
  cmd+="set title \"envmap through the lobe contract (split sum, specular=dominant) vs the Monte Carlo reference of each model's own f: $2\nspecular lobe alone (base colour black), unit sphere ${size}x${size}, reference ${refs} frames x 64 samples, $4\nthe split sum's noise (spread of a 16-frame still's samples, the largest over these rows): $noise\";"
  cmd+="set xlabel 'GGX alpha (blinn-gloss: the power of the same alpha)'; set ylabel '$2'; set grid; set key top right;"
  cmd+="set yrange [0:*];"
  plot="plot"
  for e in courtyard city sky; do
    case $e in courtyard) dt=1; pb=7; pg=5;; city) dt=4; pb=9; pg=11;; sky) dt=2; pb=6; pg=4;; esac
    label=$e; [ $e = sky ] && label='sky (no sun)'
    [ -s "$tmp/$e-blinn-gloss.csv" ] || continue
    plot+=" '$tmp/$e-blinn-gloss.csv' using 3:$3 with linespoints pt $pb dt $dt lw 2 lc rgb 'red' title 'blinn-gloss, $label',"
    plot+=" '$tmp/$e-ggx.csv' using 3:$3 with linespoints pt $pg dt $dt lw 2 lc rgb 'dark-violet' title 'ggx, $label',"
  done
  [ -s "$tmp/noisy.csv" ] && plot+=" $(gp_noisy "$tmp/noisy.csv" 3 "$3" | sed "s/ title '.*'$/ title 'noisy (its frames scatter visibly)'/"),"
  cmd+="${plot%,}"
  gp 960,560 10 "$cmd"
}
chart "$out/lobes.png" "relative RMS" 6 "3x3 block means over n.v > 0.2"
chart "$out/lobes-flip.png" "mean FLIP" 8 "FLIP per pixel over n.v > 0.2"
echo "wrote $out/lobes.csv, $out/lobes.png, $out/lobes-flip.png"
