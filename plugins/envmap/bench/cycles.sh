#!/usr/bin/env bash
# envmap's specular methods against Blender's Cycles (docs/xcheck.md), first frame: a row of
# white metal spheres (GGX alpha 0.05 / 0.2 / 0.4 / 0.7 / 1, F0 = 1) under Blender's forest.exr,
# environment only, 480x96, aa off, one frame (no accumulation, no TAA still); relative RMS per
# sphere interior from shadelab-xcheck, its FLIP (LDR-FLIP at the exposure that puts Cycles'
# 99th-percentile luminance at 1) and the noise of the setting's frames (shadelab-xcheck --noise
# 16: shadelab-bench's measure, the per-pixel spread of samples 0..15 of a 16-frame still, each
# rendered on its own, sRGB at FLIP's exposure, RMS over the sphere; tools/bench/include/bench/
# metrics.h), plus EEVEE (1 and 16 samples) against the same Cycles image (its noise not measured:
# empty). REFERENCE: `full` (the default: the row path-traced, each sphere seeing its neighbours)
# or `unoccluded` (shadelab-xcheck --unoccluded: spheres seen by camera rays only, so each is lit
# by the environment alone, the quantity envmap computes; docs/xcheck.md). Writes
# bench/cycles.csv (full) or bench/cycles-unoccluded.csv: method, alpha, relative RMS, mean ratio,
# FLIP, noise.
# The Cycles image is rendered once (SAMPLES per pixel, ≈ 8–30 min at 2048 on 2 loaded cores) and
# cached by xcheck.
# MAP (default forest) is another of Blender's studio lights (courtyard, city, …): its CSV is
# cycles[-unoccluded]-MAP.csv. $CYCLES_METHODS (names from the list below, space-separated)
# limits the run to those methods; `reference` renders (or finds cached) the Cycles image only.
# $CYCLES_EXTRA adds methods: "NAME ARGS...;NAME ARGS..." (ARGS as for shadelab-xcheck, --set …).
# Usage: plugins/envmap/bench/cycles.sh [BUILD_DIR] [SAMPLES] [OUT_DIR] [full|unoccluded] [MAP]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
samples=${2:-2048}
out=${3:-$here}
reference=${4:-full}
map=${5:-forest}
case $reference in
  full) csv=cycles ref_opt=() ;;
  unoccluded) csv=cycles-unoccluded ref_opt=(--unoccluded) ;;
  *) echo "cycles.sh: reference \"$reference\": expected full or unoccluded" >&2; exit 1 ;;
esac
[ "$map" = forest ] && csv=$csv.csv || csv=$csv-$map.csv
hdr=$(blender_hdr "$map")
[ -n "$hdr" ] || { echo "cycles.sh: Blender's $map.exr is not installed (Debian blender-data)" >&2; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
metal_row "$map" "$hdr" > "$tmp/metal_row.json"
wanted() { [ -z "${CYCLES_METHODS:-}" ] || [[ " $CYCLES_METHODS " == *" $1 "* ]]; }
if [ "${CYCLES_METHODS:-}" = reference ]; then # the Cycles image alone (cached by xcheck)
  "$build/shadelab-xcheck" "$tmp/metal_row.json" --size 480x96 --samples "$samples" --out "$tmp/ref" \
    --reference-only ${ref_opt[@]+"${ref_opt[@]}"} > "$tmp/ref.log" 2>&1 || { cat "$tmp/ref.log" >&2; exit 1; }
  exit 0
fi
xcheck() { # NAME ARGS...: one shadelab setting against the (cached) Cycles image
  local name=$1; shift
  wanted "$name" || return 0
  "$build/shadelab-xcheck" "$tmp/metal_row.json" --size 480x96 --samples "$samples" --set aa.enabled=false \
    --frames 1 --noise 16 --out "$tmp/$name" ${ref_opt[@]+"${ref_opt[@]}"} "$@" > "$tmp/$name.log" 2>&1 || { cat "$tmp/$name.log" >&2; exit 1; }
  jq -r --arg m "$name" '.objects[] | [$m, (.name | ltrimstr("s")), .rel_rms, .mean_ratio, .flip, .noise] | @csv' "$tmp/$name/report.json"
  # EEVEE per sphere, on the interiors xcheck used (its report's eevee[k].objects)
  jq -r '.eevee // [] | .[] | .samples as $n | .objects[] |
    ["eevee-\($n)", (.name | ltrimstr("s")), .rel_rms, .mean_ratio, .flip, ""] | @csv' "$tmp/$name/report.json"
}
{ echo "method,alpha,rel_rms,mean_ratio,flip,noise"
  xcheck dominant --set envmap.specular=dominant --eevee 1,16
  xcheck fitted --set envmap.specular=fitted # the default: three lookups fitted to the lobe
  xcheck mirror --set envmap.specular=mirror
  F=(--set envmap.specular=filtered)
  xcheck filtered "${F[@]}" # its defaults: 48 samples, lod bias 1, deconvolve 3, dominant from alpha 1
  xcheck filtered-still "${F[@]}" --set aa.enabled=true --frames 16 # a TAA still: the set turns per frame
  xcheck filtered32 "${F[@]}" --set envmap.filtered_samples=32
  xcheck filtered64 "${F[@]}" --set envmap.filtered_samples=64
  xcheck filtered-every-alpha "${F[@]}" --set envmap.filtered_alpha=2
  xcheck filtered-no-deconvolve "${F[@]}" --set envmap.filtered_deconvolve=0
  xcheck filtered64-bias1.5 "${F[@]}" --set envmap.filtered_samples=64 --set envmap.filtered_lod_bias=1.5 --set envmap.filtered_deconvolve=4
  xcheck filtered48-before "${F[@]}" --set envmap.filtered_lod_bias=0.5 --set envmap.filtered_deconvolve=0 --set envmap.filtered_alpha=2
  xcheck fis32 --set envmap.specular=fis --set envmap.fis_samples=32
  xcheck hybrid16 --set envmap.specular=hybrid
  xcheck hybrid16-still --set envmap.specular=hybrid --set aa.enabled=true --frames 16
  IFS=';' read -ra extra <<< "${CYCLES_EXTRA:-}"
  for e in ${extra[@]+"${extra[@]}"}; do
    read -ra words <<< "$e"
    [ ${#words[@]} -eq 0 ] || xcheck "${words[@]}"
  done; } | tr -d '"' | awk -F, 'NR == 1 || $1 !~ /^eevee-/ { print; next } { e[++n] = $0 } END { for (i = 1; i <= n; i++) print e[i] }' > "$out/$csv"
echo "$out/$csv" >&2
