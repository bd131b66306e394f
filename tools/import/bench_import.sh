#!/usr/bin/env bash
# Import benchmark (issue 14): a generated 10 M-triangle binary PLY or OBJ (a 2237² vertex grid)
# opened headless; prints the import time (the viewer's own progress line), the wall time to
# the first frame and the peak memory. A benchmark, not a test: absolute times depend on the load.
# With "compare" (OBJ only) the import alone also runs through each reader (BUILD/tools/import_file:
# the project's OBJ reader, then assimp's, which takes minutes and about 6 GB at 10 M triangles),
# each under /usr/bin/time -v: wall, CPU and peak memory.
#   usage: tools/import/bench_import.sh [BUILD_DIR] [GRID_N] [ply|obj] [compare]
set -euo pipefail
BUILD=${1:-build} N=${2:-2237} FMT=${3:-ply} COMPARE=${4:-}
SL=$(realpath "$BUILD/shadelab")
T=$(mktemp -d "${TMPDIR:-/tmp}/shadelab-import.XXXXXX")
trap 'rm -rf "$T"' EXIT
cc -O2 -o "$T/gen" "$(dirname "$0")/make_grid_ply.c" -lm
"$T/gen" "$N" "$T/grid.$FMT"
echo '{"materials": [{"name": "m"}], "nodes": [{"mesh": {"file": "grid.'"$FMT"'"}, "material": "m"}], "lights": [{"type": "directional"}]}' >"$T/grid.json"
echo "file: $(du -h "$T/grid.$FMT" | cut -f1), $((2 * (N - 1) * (N - 1))) triangles; load average $(cut -d' ' -f1-3 /proc/loadavg)"
/usr/bin/time -v "$SL" --headless --size 64x64 --scene "$T/grid.json" --output "$T/out.png" >"$T/log" 2>&1
grep -E "imported|Elapsed|Maximum resident" "$T/log" | sed 's/^[[:space:]]*//'
if [ "$COMPARE" = compare ] && [ "$FMT" = obj ]; then
  for reader in obj assimp; do
    /usr/bin/time -v "$BUILD/tools/import_file" $reader "$T/grid.obj" >"$T/$reader.log" 2>&1 || true
    grep -E "reader:|Elapsed|Maximum resident|User time|System time|rror" "$T/$reader.log" | sed 's/^[[:space:]]*//'
  done
fi
