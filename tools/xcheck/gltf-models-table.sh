#!/usr/bin/env bash
# Regenerates the conformance table of docs/models.md from its one list, tests/data/gltf_models.tsv
# (ctest gltf_models checks that list against the reader): every glTF2 model of Debian's
# assimp-testmodels and every feature file tests/test_gltf_models.c writes from the specification,
# with what shadelab's reader makes of it and, as columns of the same row, the render against
# Blender's glTF importer rendered by Cycles (shadelab-xcheck FILE, docs/xcheck.md): a reader and a
# renderer no one here wrote. A row shadelab refuses, or Blender's importer refuses, says so.
#
#   tools/xcheck/gltf-models-table.sh [BUILD_DIR]          (default build)
#
# Environment: SIZE (128x128), SAMPLES (Cycles, 64), REFERENCE (unoccluded, the default: each
# object lit by the environment alone, so the figure is the material and its import, not the
# occlusion shadelab does not model; "full" for the whole scene path-traced), MODELS (the model
# directory, /usr/share/assimp/models/glTF2), MATCH (an extended regular expression: only the rows
# whose file matches are measured, the others say "not measured: not in MATCH"), KEEP (a
# directory that keeps every row's report and side-by-side image; default a temporary one), OUT
# (docs/models.md; "-" prints the section). References are cached by shadelab-xcheck. About 15 s
# a row on two busy cores without cached references. A benchmark of conformance: it prints
# figures and asserts nothing (ctest gltf_models asserts the reader's columns).
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=$(cd "${1:-$ROOT/build}" && pwd) || exit 1
# the figures are the checkout's: bring the build up to date first (a no-op when it is)
cmake --build "$BUILD" -j"$(nproc)" > /dev/null || { echo "gltf-models-table: $BUILD does not build: fix it or pass another build directory" >&2; exit 1; }
SIZE=${SIZE:-128x128}
SAMPLES=${SAMPLES:-64}
REFERENCE=${REFERENCE:-unoccluded}
MODELS=${MODELS:-/usr/share/assimp/models/glTF2}
OUT=${OUT:-$ROOT/docs/models.md}
TABLE=$ROOT/tests/data/gltf_models.tsv
XC=$BUILD/shadelab-xcheck
WRITER=$BUILD/tests/test_gltf_models
for exe in "$XC" "$WRITER"; do
    [ -x "$exe" ] || { echo "gltf-models-table: no $exe (build with tests first, or pass the build dir)" >&2; exit 1; }
done
[ -d "$MODELS" ] || { echo "gltf-models-table: no $MODELS (tools/install-deps.sh --with-tests installs assimp-testmodels)" >&2; exit 1; }
case $REFERENCE in unoccluded) ref_args=(--unoccluded) ;; full) ref_args=() ;;
    *) echo "gltf-models-table: REFERENCE=$REFERENCE: expected unoccluded or full" >&2; exit 1 ;; esac
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
WORK=${KEEP:-$TMP/work}
mkdir -p "$WORK" || exit 1
T0=$(date +%s)
LOAD0=$(cut -d' ' -f1-3 /proc/loadavg)

# The feature files, as the test writes them (its --print is the table as the code sees it today:
# a difference from the list means the list is stale, which ctest gltf_models reports).
SL_TEST_OUT=$TMP/features "$WRITER" --print > "$TMP/print.tsv" 2> "$TMP/print.log" ||
    { echo "gltf-models-table: $WRITER --print failed:" >&2; cat "$TMP/print.log" >&2; exit 1; }
diff <(grep -v '^#' "$TABLE") <(grep -v '^#' "$TMP/print.tsv") > /dev/null ||
    echo "gltf-models-table: warning: $TABLE differs from the reader today (ctest -R gltf_models says how); the list is used" >&2
FEATURES=$TMP/features/gltf_models

# One line per row of the list: KEY|RESULT, RESULT a report.json, or "not measured: why".
grep -v '^#' "$TABLE" | grep -v '^$' > "$TMP/list"
total=$(wc -l < "$TMP/list")
i=0
: > "$TMP/rows"
while IFS=$'\t' read -r key outcome _; do
    i=$((i + 1))
    case $key in feature/*) file=$FEATURES/${key#feature/}.glb ;; *) file=$MODELS/$key ;; esac
    if [ "$outcome" != ok ]; then echo "$key|not measured: shadelab refuses the file" >> "$TMP/rows"; continue; fi
    if ! echo "$key" | grep -qE "${MATCH:-.}"; then echo "$key|not measured: not in MATCH" >> "$TMP/rows"; continue; fi
    name=$(echo "$key" | tr '/' '_')
    echo "gltf-models-table: [$i/$total] $key" >&2
    if "$XC" "${ref_args[@]}" --size "$SIZE" --samples "$SAMPLES" --out "$WORK/$name" "$file" \
        > "$WORK/$name.log" 2>&1 && [ -f "$WORK/$name/report.json" ]; then
        echo "$key|$WORK/$name/report.json" >> "$TMP/rows"
    elif grep -q 'exit status 2 (the report was written)' "$WORK/$name.log"; then
        echo "$key|not measured: shadelab printed errors: $(grep -m1 '^error' "$WORK/$name.log" | cut -c1-140)" >> "$TMP/rows"
    elif why=$(grep -E '^[A-Za-z]*(Error|Exception): ' "$WORK/$name/blender.log" 2>/dev/null | grep -v '^xcheck-blender' |
               tail -1) && [ -n "$why" ]; then
        echo "$key|not measured: Blender's importer: $(echo "$why" | cut -c1-160)" >> "$TMP/rows"
    else
        echo "$key|not measured: $(grep -v '^\[' "$WORK/$name.log" | tail -1 | cut -c1-160)" >> "$TMP/rows"
    fi
done < "$TMP/list"

COMMIT=$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)
python3 - "$TMP/section.md" "$TMP/list" "$TMP/rows" "$SIZE" "$SAMPLES" "$REFERENCE" "$COMMIT" "$LOAD0" \
    "$(cut -d' ' -f1-3 /proc/loadavg)" "$(( ($(date +%s) - T0) / 60 ))" <<'PY'
import json, sys, time
out, listed, rows, size, samples, reference, commit, load0, load1, minutes = sys.argv[1:11]

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
    return rel, flip, ratio, len(objs), len(r["objects"]) - len(objs)

def plural(n, word):
    return f"{n} {word}" + ("" if n == 1 else "es" if word.endswith("sh") else "s")

def reader(fields):
    """What shadelab's reader makes of the file (the list's columns), and its stated expectations."""
    if fields[0] != "ok":
        return "refused", "—", fields[1] if len(fields) > 1 else ""
    meshes, textures, cameras, lights = (int(x) for x in fields[1:5])
    parts = [plural(meshes, "mesh")] + [plural(n, w) for n, w in ((textures, "texture"), (cameras, "camera"), (lights, "light")) if n]
    met = fields[5].replace(",", ", ") if len(fields) > 5 else "—"
    return ", ".join(parts), met, ""

results = dict(row.rstrip("\n").split("|", 1) for row in open(rows))
lines, figures, unmeasured = [], [], 0
for row in open(listed):
    key, *fields = row.rstrip("\n").split("\t")
    opens, met, cause = reader(fields)
    what = results[key]
    name = f"`{key}`"
    if what.startswith("not measured"):
        unmeasured += 1
        note = f"not measured: shadelab refuses it ({cause.split(' (a warning')[0]})" if cause else what
        lines.append(f"| {name} | {opens} | {met} | — | — | — | {note.replace('|', '/')} |")
        continue
    r = json.load(open(what))
    s = summary(r)
    notes = [n for n in r.get("notes", []) if not n.startswith(("not cross-checked: tonemap", "glTF: geometry",
                                                                         "approximated: glTF metallic-roughness as Cycles' Principled"))]
    note = "; ".join(n.replace("|", "/") for n in notes)[:300]
    if s is None:
        unmeasured += 1
        lines.append(f"| {name} | {opens} | {met} | — | — | — | not measured: no object pixels; {note} |")
        continue
    rel, flip, ratio, n, left = s
    figures.append(rel)
    objs = plural(n, "object") + (f" (+{left} not)" if left else "") if n != 1 or left else ""
    note = "; ".join(x for x in (objs, note) if x)
    lines.append(f"| {name} | {opens} | {met} | {rel:.3f} | {flip:.3f} | {ratio:.2f} | {note} |")

with open(out, "w") as f:
    f.write("<!-- gltf-models-table begin: generated by tools/xcheck/gltf-models-table.sh; do not edit by hand -->\n")
    f.write(f"Generated by `tools/xcheck/gltf-models-table.sh` from `tests/data/gltf_models.tsv` "
            f"(`shadelab-xcheck {'--unoccluded ' if reference == 'unoccluded' else ''}--size {size} --samples {samples} FILE` "
            f"per row) on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} at commit {commit}; load average {load0} "
            f"at the start, {load1} at the end, {minutes} min. **opens** and **expectations met** are the list's "
            "(what the reader makes of the file; a feature file's expectations are stated in the file itself, and "
            "ctest `gltf_models` checks both). The last columns render the file as a model (its bounds framed or its "
            "own camera, the default environment, no JSON) in shadelab, and as Blender's glTF importer reads the same "
            "file in Cycles, compared before tone mapping on each object's interior; the reference is " +
            ("**unoccluded** (objects seen by camera rays only: the material and its import, not the occlusion "
             "shadelab does not model)" if reference == "unoccluded" else "the whole scene path-traced") +
            ". rel-RMS and the ratio of means (shadelab / Cycles) over the cross-checked objects' pixels, FLIP their "
            "pixel-weighted mean; notes are the exporter's (approximations, what is not cross-checked). Blender's "
            "Principled BSDF is not glTF's BRDF (below the table).\n\n")
    f.write("| file | opens | expectations met | rel-RMS | FLIP | ratio | notes |\n|---|---|---|---|---|---|---|\n")
    f.write("\n".join(lines) + "\n\n")
    if figures:
        figures.sort()
        f.write(f"{len(lines)} rows: {len(figures)} measured against Cycles (median rel-RMS {figures[len(figures) // 2]:.3f}), "
                f"{unmeasured} not.\n")
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
