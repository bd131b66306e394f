#!/usr/bin/env bash
# Opening a big glTF: time to the first frame and peak memory (a benchmark, not a test).
#   tools/gltf/bench_open.sh [BUILD_DIR] [N] [TEXTURE_SIZE]
# Writes /tmp/shadelab-big.glb once (tools/gltf/make_big_glb.py: 2 N² triangles, two
# TEXTURE_SIZE² noise textures embedded; N = 1000, 4096 by default: 2 M triangles, ~135 MB), then
# opens it headless (640×360) with --stats and prints the import progress, the start-up to first
# frame and the peak resident memory (getrusage; llvmpipe's textures count there too).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../../build}
n=${2:-1000}
tex=${3:-4096}
glb=/tmp/shadelab-big-$n-$tex.glb
[ -f "$glb" ] || python3 "$here/make_big_glb.py" "$glb" "$n" "$tex"
stats=$(mktemp /tmp/shadelab-big-stats.XXXXXX.json)
"$build/shadelab" --headless --size 640x360 --output /tmp/shadelab-big.png --stats "$stats" "$glb" 2>&1 |
  grep -v "prefilter 256"
python3 - "$stats" "$glb" <<'PY'
import json, os, sys
s = json.load(open(sys.argv[1]))
print(f"{os.path.basename(sys.argv[2])}: {os.path.getsize(sys.argv[2]) / 1e6:.1f} MB; start-up to first frame "
      f"{s['startup_to_first_frame_ms'] / 1000:.1f} s; peak memory {s['peak_rss_mib']:.0f} MiB; backend {s['backend']}")
PY
rm -f "$stats"
