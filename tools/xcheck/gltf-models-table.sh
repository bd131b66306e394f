#!/usr/bin/env bash
# Regenerates the "Against Blender's importer" section of docs/models.md: every glTF2 model of
# Debian's assimp-testmodels that the conformance table (tests/data/gltf_models.tsv, its one list)
# opens as "ok", rendered by shadelab as a model (no JSON) and by Cycles from Blender's own glTF
# importer (shadelab-xcheck MODEL, docs/xcheck.md) — a reader and a renderer no one here wrote.
#
#   tools/xcheck/gltf-models-table.sh [BUILD_DIR]          (default build)
#
# Environment: SIZE (128x128), SAMPLES (Cycles, 64), REFERENCE (unoccluded, the default: each
# object lit by the environment alone, so the figure is the material and its import, not the
# occlusion shadelab does not model; "full" for the whole scene path-traced), MODELS (the model
# directory, /usr/share/assimp/models/glTF2), MATCH (an extended regular expression: only the models
# whose path matches), KEEP (a directory that keeps every row's report and
# side-by-side image; default a temporary one), OUT (docs/models.md; "-" prints the section).
# References are cached by shadelab-xcheck. About 25 s a model on two busy cores without cached
# references. A benchmark of conformance: it prints figures and asserts nothing.
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=$(cd "${1:-$ROOT/build}" && pwd) || exit 1
SIZE=${SIZE:-128x128}
SAMPLES=${SAMPLES:-64}
REFERENCE=${REFERENCE:-unoccluded}
MODELS=${MODELS:-/usr/share/assimp/models/glTF2}
OUT=${OUT:-$ROOT/docs/models.md}
XC=$BUILD/shadelab-xcheck
[ -x "$XC" ] || { echo "gltf-models-table: no $XC (build first, or pass the build dir)" >&2; exit 1; }
[ -d "$MODELS" ] || { echo "gltf-models-table: no $MODELS (tools/install-deps.sh --with-tests installs assimp-testmodels)" >&2; exit 1; }
case $REFERENCE in unoccluded) ref_args=(--unoccluded) ;; full) ref_args=() ;;
    *) echo "gltf-models-table: REFERENCE=$REFERENCE: expected unoccluded or full" >&2; exit 1 ;; esac
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
WORK=${KEEP:-$TMP/rows}
mkdir -p "$WORK" || exit 1
T0=$(date +%s)
LOAD0=$(cut -d' ' -f1-3 /proc/loadavg)

# The list: the conformance table's glTF2 models that open (feature/ rows are written by its test).
grep -v '^#' "$ROOT/tests/data/gltf_models.tsv" | awk -F'\t' '$2 == "ok" && $1 !~ /^feature\//' | cut -f1 |
    grep -E "${MATCH:-.}" > "$TMP/list"
total=$(wc -l < "$TMP/list")
i=0
: > "$TMP/rows"
while read -r model; do
    i=$((i + 1))
    name=$(echo "$model" | tr '/' '_')
    echo "gltf-models-table: [$i/$total] $model" >&2
    if "$XC" "${ref_args[@]}" --size "$SIZE" --samples "$SAMPLES" --out "$WORK/$name" "$MODELS/$model" \
        > "$WORK/$name.log" 2>&1 && [ -f "$WORK/$name/report.json" ]; then
        echo "$model|$WORK/$name/report.json" >> "$TMP/rows"
    elif why=$(grep -E '^[A-Za-z]*(Error|Exception): ' "$WORK/$name/blender.log" 2>/dev/null | grep -v '^xcheck-blender' |
               tail -1) && [ -n "$why" ]; then
        echo "$model|FAILED: Blender's importer: $(echo "$why" | cut -c1-160)" >> "$TMP/rows"
    else
        echo "$model|FAILED: $(grep -v '^\[' "$WORK/$name.log" | tail -1 | cut -c1-160)" >> "$TMP/rows"
    fi
done < "$TMP/list"

COMMIT=$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)
python3 - "$TMP/section.md" "$TMP/rows" "$SIZE" "$SAMPLES" "$REFERENCE" "$COMMIT" "$LOAD0" \
    "$(cut -d' ' -f1-3 /proc/loadavg)" "$(( ($(date +%s) - T0) / 60 ))" <<'PY'
import json, sys, time
out, rows, size, samples, reference, commit, load0, load1, minutes = sys.argv[1:10]

def summary(r):
    """The cross-checked objects together: pixel-weighted FLIP, the root of the pixel-weighted
    mean square relative error, and the ratio of the means (shadelab / Cycles)."""
    objs = [o for o in r["objects"] if o["cross_checked"] and o["pixels"] > 0]
    p = sum(o["pixels"] for o in objs)
    if not p:
        return None
    rel = (sum(o["pixels"] * o["rel_rms"] ** 2 for o in objs) / p) ** 0.5
    flip = sum(o["pixels"] * o["flip"] for o in objs) / p
    cyc = sum(o["pixels"] * o["mean_cycles"] for o in objs)
    ratio = sum(o["pixels"] * o["mean_shadelab"] for o in objs) / cyc if cyc > 0 else float("nan")
    left = len(r["objects"]) - len(objs)
    return rel, flip, ratio, len(objs), left

lines, figures = [], []
for row in open(rows):
    model, what = row.rstrip("\n").split("|", 1)
    if what.startswith("FAILED"):
        lines.append(f"| `{model}` | — | — | — | — | {what} |")
        continue
    r = json.load(open(what))
    s = summary(r)
    notes = [n for n in r.get("notes", []) if not n.startswith(("not cross-checked: tonemap", "glTF: geometry"))]
    note = "; ".join(n.replace("|", "/") for n in notes)[:300]
    if s is None:
        lines.append(f"| `{model}` | — | — | — | 0 | nothing cross-checked (no object pixels); {note} |")
        continue
    rel, flip, ratio, n, left = s
    figures.append((rel, flip, ratio))
    objs = f"{n}" + (f" (+{left} not)" if left else "")
    lines.append(f"| `{model}` | {rel:.3f} | {flip:.3f} | {ratio:.2f} | {objs} | {note} |")

with open(out, "w") as f:
    f.write("<!-- gltf-models-table begin: generated by tools/xcheck/gltf-models-table.sh; do not edit by hand -->\n")
    f.write("### Against Blender's importer and Cycles\n\n")
    f.write(f"Generated by `tools/xcheck/gltf-models-table.sh` (`shadelab-xcheck {'--unoccluded ' if reference == 'unoccluded' else ''}"
            f"--size {size} --samples {samples} MODEL` per row) on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} "
            f"at commit {commit}; load average {load0} at the start, {load1} at the end, {minutes} min. "
            "Each model as a model (its bounds framed, the default environment, no JSON) in shadelab, and as "
            "Blender's glTF importer reads the same file in Cycles, compared before tone mapping on each object's "
            "interior; the reference is " +
            ("**unoccluded** (objects seen by camera rays only: the material and its import, not the occlusion "
             "shadelab does not model)" if reference == "unoccluded" else "the whole scene path-traced") +
            ". rel-RMS and the ratio of means (shadelab / Cycles) over the cross-checked objects' pixels, FLIP "
            "their pixel-weighted mean; notes are the exporter's (approximations, what is not cross-checked). "
            "Blender's Principled BSDF is not glTF's BRDF (Burley diffuse, no (1 − F) on the diffuse): a few "
            "per cent of every row is that.\n\n")
    f.write("| model | rel-RMS | FLIP | ratio | objects | notes |\n|---|---|---|---|---|---|\n")
    f.write("\n".join(lines) + "\n\n")
    if figures:
        figures.sort()
        med = figures[len(figures) // 2]
        f.write(f"{len(figures)} models measured; median rel-RMS {med[0]:.3f}.\n")
    f.write("<!-- gltf-models-table end -->\n")
PY
if [ "$OUT" = - ]; then cat "$TMP/section.md"; exit 0; fi
python3 - "$OUT" "$TMP/section.md" <<'PY'
import re, sys
path, section = sys.argv[1], open(sys.argv[2]).read()
text = open(path).read()
pattern = re.compile(r"<!-- gltf-models-table begin.*?<!-- gltf-models-table end -->\n?", re.S)
text = pattern.sub(lambda m: section, text) if pattern.search(text) else text.rstrip("\n") + "\n\n" + section
open(path, "w").write(text)
PY
echo "gltf-models-table: wrote $OUT" >&2
