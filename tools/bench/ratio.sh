#!/usr/bin/env bash
# Ratio benchmark against the hand-written floor (../shared/bench/baseline_ggx.c): shadelab's frame
# on scenes/ratio_sphere.json over the baseline's, interleaved, per size and light count, with the
# load average (docs/benchmarks.md holds the current 720p figures, from tools/bench/benchmarks-table.sh).
#   tools/bench/ratio.sh [--build DIR] [--quick] [--rounds N] [--sizes WxH,..] [--lights N,..] [--shared DIR]
# Without ../shared (or --shared DIR) it says so and exits 0.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="${SHADELAB_BUILD:-$root/build}"
args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build="$2"; shift 2 ;;
    *) args+=("$1"); shift ;;
  esac
done
exe="$build/shadelab"
if [ ! -x "$exe" ]; then
  echo "ratio: $exe not found: build first (./build.sh) or pass --build DIR" >&2
  exit 1
fi
command -v python3 >/dev/null || { echo "ratio: needs python3" >&2; exit 1; }
exec python3 "$root/tools/bench/ratio.py" --shadelab "$exe" "${args[@]}"
