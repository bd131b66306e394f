#!/usr/bin/env bash
# The cost and error model envmap registers for envmap.specular with the window's frame-time
# budget (docs/budget.md, sdk/include/shadelab/ext/budget.h): settings dominant, fitted and filtered.
#   cost   the whole frame of SCENE (default: the built-in scene, as core.render_scale's model) at
#          1280x720 on OSMesa, `shadelab --headless --bench` (median of 7 frames after 3), the
#          settings interleaved round by round (the machine is shared: compare within a round);
#          a setting's cost = its frame time over filtered's in the same round, the mean of the
#          rounds' ratios
#   error  RMSE of linear radiance against envmap's declared reference (64 frames x 64 samples,
#          shadelab-bench, cached) at 320x180, aa off: one frame, what a frame in motion shows;
#          shadelab-bench's noise measure (16 frames of a still, each on its own) beside it
# Writes bench/budget.csv (setting, cost, rmse, noise, frame ms per round) and prints it. A
# benchmark: it asserts nothing; envmap.c declares the figures it printed.
# Usage: plugins/envmap/bench/budget.sh [BUILD_DIR] [ROUNDS] [SCENE]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
rounds=${2:-3}
scene=${3:-}
scene_opt=()
[ -z "$scene" ] || scene_opt=(--scene "$scene")
settings=(dominant fitted filtered)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for r in $(seq 1 "$rounds"); do
  for s in "${settings[@]}"; do
    SHADELAB_PLUGIN_PATH="$build/plugins" "$build/shadelab" --headless ${scene_opt[@]+"${scene_opt[@]}"} \
      --size 1280x720 --frames 10 --bench --set "envmap.specular=$s" 2>/dev/null |
      awk -v s="$s" '$1 == "frame" { print s, $4 }' >> "$tmp/ms.txt"
  done
done
"$build/shadelab-bench" --plugin envmap ${scene_opt[@]+"${scene_opt[@]}"} --size 320x180 --set aa.enabled=false \
  --frames 3 --warmup 2 --no-chart --out "$tmp/err" \
  $(for s in "${settings[@]}"; do printf -- '--settings envmap.specular=%s ' "$s"; done) > "$tmp/bench.log" 2>&1 ||
  { cat "$tmp/bench.log" >&2; exit 1; }
{ echo "setting,cost,rmse,noise,frame_ms_per_round"
  for s in "${settings[@]}"; do
    cost=$(awk -v s="$s" -v last="${settings[-1]}" '{ ms[$1, ++n[$1]] = $2 }
      END { t = 0; for (i = 1; i <= n[s]; i++) t += ms[s, i] / ms[last, i]; printf "%.3f", t / n[s] }' "$tmp/ms.txt")
    per_round=$(awk -v s="$s" '$1 == s { printf "%s%s", sep, $2; sep = " " }' "$tmp/ms.txt")
    err=$(jq -r --arg s "envmap.specular=$s" '.settings[] | select(.settings == $s) | "\(.error.rmse),\(.error.noise)"' "$tmp/err.json")
    echo "$s,$cost,$err,$per_round"
  done
  echo "# $(date -u +%FT%RZ), commit $(git -C "$root" rev-parse --short HEAD), scene ${scene:-built-in}, load average $(cut -d' ' -f1-3 /proc/loadavg)"
} > "$here/budget.csv"
cat "$here/budget.csv"
