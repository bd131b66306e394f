#!/usr/bin/env bash
# envmap's image-based lighting term by term against its Monte Carlo reference (issue 16): the
# diffuse and the specular part of metal and dielectric spheres separately, per alpha, and a
# Lambert sphere (irradiance alone, SH and convolved), each binned by n·v, on the procedural sky
# without its sun and Blender's courtyard.exr (Debian blender-data; skipped when absent).
# Usage: plugins/envmap/bench/terms.sh [BUILD_DIR] [OUT_DIR] [SIZE] [REFERENCE_FRAMES] [-- MORE ARGS]
# Writes OUT_DIR/terms.csv; MORE ARGS go to envmap_bench_terms (e.g. --set "envmap.specular=fis").
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
out=${2:-$here}
size=${3:-48}
refs=${4:-32}
shift $(( $# < 4 ? $# : 4 )); [ "${1:-}" = -- ] && shift
envs=(--env sky:0)
hdr=$(blender_hdr "${HDR:-courtyard}")
[ -n "$hdr" ] && envs=(--env sky:0 --env "$hdr")
export SHADELAB_CACHE=${SHADELAB_CACHE:-$(mktemp -d)}
SHADELAB_PLUGIN_PATH="$build/plugins" "$build/plugins/envmap/envmap_bench_terms" --size "$size" --reference-frames "$refs" \
  "${envs[@]}" "$@" > "$out/terms.csv"
echo "wrote $out/terms.csv"
