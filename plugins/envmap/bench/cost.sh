#!/usr/bin/env bash
# The per-pixel cost of envmap's specular methods at 1280×720 (issue 16): scenes/ibl_spheres.json
# (GGX floor and spheres under the procedural sky; nearly every pixel is GGX), OSMesa/llvmpipe,
# the forward pass's median over 7 frames after 3 warm-up (shadelab --bench), methods interleaved
# round by round (the machine is shared: compare within a round). Prints a CSV
# round,method,forward_ms,frame_ms,ns_per_pixel and the load average. A METHOD is an
# envmap.specular value, or VALUE:N for fis or filtered with N samples (envmap.VALUE_samples=N),
# or VALUE:N:P=X,Q=Y with more envmap parameters (envmap.P=X, envmap.Q=Y).
# Usage: plugins/envmap/bench/cost.sh [BUILD_DIR] [ROUNDS] [METHOD...]   (default: dominant hybrid)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
rounds=${2:-3}
shift $(( $# > 2 ? 2 : $# ))
methods=("$@")
[ ${#methods[@]} -gt 0 ] || methods=(dominant hybrid)
echo "round,method,forward_ms,frame_ms,ns_per_pixel"
for r in $(seq 1 "$rounds"); do
  for m in "${methods[@]}"; do
    sets=(--set "envmap.specular=${m%%:*}")
    rest=${m#*:}
    [ "$m" = "${m%%:*}" ] || sets+=(--set "envmap.${m%%:*}_samples=${rest%%:*}")
    if [ "$rest" != "${rest#*:}" ]; then
      IFS=, read -ra more <<< "${rest#*:}"
      for p in "${more[@]}"; do sets+=(--set "envmap.$p"); done
    fi
    SHADELAB_PLUGIN_PATH="$build/plugins" "$build/shadelab" --headless --scene "$root/scenes/ibl_spheres.json" \
      --size 1280x720 --frames 10 --bench "${sets[@]}" 2>/dev/null |
      awk -v r="$r" -v m="$m" '$1 == "forward" { f = $2 } $1 == "frame" { w = $4 }
        END { printf "%d,%s,%.1f,%.1f,%.0f\n", r, m, f, w, f * 1e6 / (1280 * 720) }'
  done
done
echo "# load average: $(cut -d' ' -f1-3 /proc/loadavg)"
