#!/usr/bin/env bash
# Error-versus-time sweeps of the spotlight-shadow filters with shadelab-bench (README.md).
#   plugins/spotlight-shadow/bench/run_bench.sh BUILD_DIR [OUT_DIR]
# Writes OUT_DIR/spheres_r0.1.{csv,json,png} (and -flip.png): every filter against the area-light reference
# (lights of radius 0.1 m, 256 hard maps of 4096² from stratified points on each light), and
# OUT_DIR/spheres_r0.{csv,json,png}: the same lights as points (r = 0) against one 8192² map,
# and OUT_DIR/shadow_pass_cost.csv: the shadow pass alone for 1, 8, 32 lights and three sizes.
# always_render=true re-renders the maps every frame, so frame times include the shadow pass
# (a static scene pays it once). Small CI runs: add --reference-accumulate 16 --frames 6.
set -eu
build=$(cd "$1" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
out=${2:-$here}
P=spotlight-shadow
# from the repository's root, so the charts name the scene as scenes/… (not this machine's path)
cd "$here/../../.."
scenes=scenes
# aa off: the filters against the reference frame by frame (with TAA's still every filter shares
# the floor its silhouettes set against the reference, RMSE 0.0052 from hard 512² to PCSS 4096²)
common=(--plugin $P --set $P.always_render=true --set aa.enabled=false --frames 15 --warmup 3 --rounds 3 --metric rmse
        --metric flip)

args=()
for m in 512 1024 2048 4096; do args+=(--settings "$P.filter=hard $P.map_size=$m"); done
for m in 1024 2048; do for k in 3 5; do args+=(--settings "$P.filter=pcf $P.map_size=$m $P.pcf_size=$k"); done; done
args+=(--settings "$P.filter=pcf $P.map_size=2048 $P.pcf_size=5 $P.pcf_step=2")
args+=(--settings "$P.filter=pcf $P.map_size=2048 $P.pcf_size=7")
args+=(--settings "$P.filter=pcf $P.map_size=4096 $P.pcf_size=5")
for m in 1024 2048; do args+=(--settings "$P.filter=poisson $P.map_size=$m $P.poisson_taps=16"); done
args+=(--settings "$P.filter=poisson $P.map_size=2048 $P.poisson_taps=32")
for m in 1024 2048; do args+=(--settings "$P.filter=pcss $P.map_size=$m $P.pcss_blocker_taps=16 $P.pcss_filter_taps=32"); done
args+=(--settings "$P.filter=pcss $P.map_size=2048 $P.pcss_blocker_taps=8 $P.pcss_filter_taps=16")
args+=(--settings "$P.filter=pcss $P.map_size=2048 $P.pcss_blocker_taps=32 $P.pcss_filter_taps=64")
args+=(--settings "$P.filter=pcss $P.map_size=4096 $P.pcss_blocker_taps=16 $P.pcss_filter_taps=32")
"$build/shadelab-bench" "${common[@]}" --scene "$scenes/spheres_shadow.json" "${args[@]}" --out "$out/spheres_r0.1"

args=()
for m in 512 1024 2048 4096; do args+=(--settings "$P.filter=hard $P.map_size=$m"); done
for m in 1024 2048; do for k in 3 5; do args+=(--settings "$P.filter=pcf $P.map_size=$m $P.pcf_size=$k"); done; done
args+=(--settings "$P.filter=pcf $P.map_size=4096 $P.pcf_size=3")
args+=(--settings "$P.filter=poisson $P.map_size=2048 $P.poisson_taps=16")
args+=(--settings "$P.filter=pcss $P.map_size=2048 $P.pcss_blocker_taps=16 $P.pcss_filter_taps=32")
"$build/shadelab-bench" "${common[@]}" --scene "$scenes/spheres_shadow.json" --set light.red.radius=0 --set light.white.radius=0 \
  --reference-settings "$P.filter=reference $P.reference_map_size=8192" --reference-accumulate 1 "${args[@]}" \
  --out "$out/spheres_r0"

echo "lights,map_size,shadow_pass_ms_median,forward_ms_median" > "$out/shadow_pass_cost.csv"
for n in 1 8 32; do
  for m in 512 1024 2048; do
    offs=()
    for k in $(seq "$n" 31); do offs+=(--set "light.s$(printf %02d "$k").enabled=false"); done
    r=$("$build/shadelab" --headless --scene "$scenes/shadow_many_spots.json" --size 320x180 --frames 14 --bench \
        --set $P.always_render=true --set $P.map_size=$m "${offs[@]}" 2>&1)
    echo "$n,$m,$(awk '/shadow-maps/{print $2}' <<<"$r"),$(awk '/ forward /{print $2}' <<<"$r")" >> "$out/shadow_pass_cost.csv"
  done
done
cat "$out/shadow_pass_cost.csv"
