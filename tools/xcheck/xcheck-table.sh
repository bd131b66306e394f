#!/usr/bin/env bash
# Regenerates the cross-check section of docs/benchmarks.md: every bundled scene Cycles can
# represent, at the plugins' defaults, at each plugin's highest setting and with the screen-space
# effects EEVEE renders with, shadelab and EEVEE against a Cycles reference (shadelab-xcheck,
# docs/xcheck.md), and the issue's figure per row.
#
#   tools/xcheck/xcheck-table.sh [BUILD_DIR]          (default build)
#
# Environment: SIZE (256x144), SAMPLES (Cycles, 256), EEVEE (sample counts, "1,16"), SCENES (the
# scene files; default: every scenes/*.json that `shadelab-xcheck --export-only` exports with
# nothing but tone mapping or the background left out of the cross-check), DATA (data directory
# for scenes that need one; default ../shared/assets beside the repository), KEEP (a directory
# that keeps every row's report and images; default a temporary one), REUSE=1 (a row whose report
# is in KEEP already is not measured again: an interrupted run resumes), LIMIT_MIN (start no new
# row after this many minutes; the rows left are listed as not measured), OUT (docs/benchmarks.md;
# "-" prints the section). The section sits between the markers below, replaced in place
# (appended when absent); tools/bench/benchmarks-table.sh keeps it when it rewrites the file.
# References are cached (shadelab-xcheck's cache: one per scene, shared by its rows); EEVEE renders
# once per scene (its figures do not depend on shadelab's settings); shadelab is timed on every
# row. About 1 hour on two busy cores without cached references, 25 minutes with them.
# A benchmark: it prints figures and asserts nothing.
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=$(cd "${1:-$ROOT/build}" && pwd) || exit 1
# the figures are the checkout's: bring the build up to date first (a no-op when it is)
cmake --build "$BUILD" -j"$(nproc)" > /dev/null || { echo "xcheck-table: $BUILD does not build: fix it or pass another build directory" >&2; exit 1; }
SIZE=${SIZE:-256x144}
SAMPLES=${SAMPLES:-256}
EEVEE=${EEVEE:-1,16}
DATA=${DATA:-$ROOT/../shared/assets}
OUT=${OUT:-$ROOT/docs/benchmarks.md}
XC=$BUILD/shadelab-xcheck
[ -x "$XC" ] || { echo "xcheck-table: no $XC (build first, or pass the build dir)" >&2; exit 1; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
WORK=${KEEP:-$TMP/work} # the rows list is $TMP/rows
mkdir -p "$WORK" || exit 1
cd "$ROOT" || exit 1
data_args=()
[ -d "$DATA" ] && data_args=(--data "$DATA")

# Each plugin's highest real-time setting (the plugins' own READMEs say why; core.ssaa=8 is the
# core's declared reference, not a real-time setting); a plugin not named here either has its
# highest setting as default (aa: taa; ggx: specular_aa on; normal-map: lod_bias 0, the right mip),
# declares no quality knob (ssao), or is not compared (tonemap: before tone mapping).
declare -A HIGHEST=(
    [core]="core.ssaa=4"
    [bounce]="bounce.vpls=32 bounce.grid=24"
    [envmap]="envmap.specular=fis envmap.fis_samples=32 envmap.irradiance=convolved envmap.reflections=screen envmap.reflections_scale=1"
    [spotlight-shadow]="spotlight-shadow.filter=pcss spotlight-shadow.map_size=4096 spotlight-shadow.pcss_blocker_taps=64 spotlight-shadow.pcss_filter_taps=64"
)
# EEVEE renders with ambient occlusion and screen-space reflections (xcheck_blender.py: use_gtao,
# use_ssr): shadelab's counterparts are the ssao plugin and envmap's screen-space reflections,
# which the scenes (and the defaults) leave off for their cost. One row per scene with them on.
eevee_effects() { # PLUGINS...: the arguments of that row
    local a=(--plugin ssao)
    [[ " $* " == *" envmap "* ]] && a+=(--set envmap.reflections=screen)
    echo "${a[@]}"
}
note() { echo "xcheck-table: $*" >&2; }

# The scenes: what the exporter says Cycles represents (left out: a reason per scene).
: > "$TMP/left_out"
if [ -z "${SCENES:-}" ]; then
    SCENES=""
    for s in scenes/*.json; do
        if ! "$XC" --export-only "${data_args[@]}" --out "$TMP/export" "$s" > "$TMP/export.log" 2>&1; then
            echo "$s|$(tail -1 "$TMP/export.log" | sed 's/^shadelab-xcheck: //')" >> "$TMP/left_out"
        elif grep '^not cross-checked:' "$TMP/export.log" | grep -qv '^not cross-checked: \(tonemap\|the background\)'; then
            echo "$s|$(grep '^not cross-checked:' "$TMP/export.log" | grep -v '^not cross-checked: \(tonemap\|the background\)' |
                       sed 's/^not cross-checked: //' | paste -sd '\t' | sed 's/\t/; /g')" >> "$TMP/left_out"
        else
            SCENES="$SCENES $s"
        fi
        rm -rf "$TMP/export"
    done
fi

# row SCENE KIND NAME ARGS...: one shadelab-xcheck run into $WORK/NAME; its report's path on rows
# (KIND: defaults, highest or effects).
: > "$TMP/rows"
: > "$TMP/not_measured"
row() {
    local scene=$1 kind=$2 name=$3 status
    shift 3
    if [ "${REUSE:-0}" = 1 ] && [ -f "$WORK/$name/report.json" ]; then
        note "$scene: $name (kept from an earlier run)"
        echo "$scene|$kind|$WORK/$name/report.json|$*" >> "$TMP/rows"
        REUSED=$((REUSED + 1))
        return
    fi
    if [ -n "${LIMIT_MIN:-}" ] && [ $(( $(date +%s) - T0 )) -ge $(( LIMIT_MIN * 60 )) ]; then
        note "$scene: $name not measured (LIMIT_MIN=$LIMIT_MIN)"
        echo "$scene ($name)" >> "$TMP/not_measured"
        return
    fi
    note "$scene: $name"
    if nice "$XC" --size "$SIZE" --samples "$SAMPLES" "${data_args[@]}" --out "$WORK/$name" "$@" "$scene" \
        > "$WORK/$name.log" 2>&1; then
        echo "$scene|$kind|$WORK/$name/report.json|$*" >> "$TMP/rows"
    else
        status=$?
        note "$scene ($name) failed ($status): $(tail -2 "$WORK/$name.log")"
        [ $status = 77 ] && exit 77
        if [ $status = 2 ]; then # shadelab printed errors: a report, but not a clean measurement
            mv "$WORK/$name/report.json" "$WORK/$name/report-with-errors.json"
            echo "$scene ($name: shadelab printed errors)" >> "$TMP/not_measured"
        fi
    fi
}

REUSED=0 LOAD0=$(cut -d' ' -f1-3 /proc/loadavg) T0=$(date +%s)
for s in $SCENES; do
    name=$(basename "$s" .json)
    row "$s" defaults "$name" --eevee "$EEVEE"
    [ -f "$WORK/$name/report.json" ] || continue
    plugins=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["plugins"].replace(",", " "))' \
              "$WORK/$name/report.json")
    for p in core $plugins; do
        [ -n "${HIGHEST[$p]:-}" ] || continue
        sets=()
        for a in ${HIGHEST[$p]}; do sets+=(--set "$a"); done
        row "$s" highest "$name-$p-highest" "${sets[@]}"
    done
    # shellcheck disable=SC2046 # the words of eevee_effects
    row "$s" effects "$name-eevee-effects" $(eevee_effects $plugins)
done
LOAD1=$(cut -d' ' -f1-3 /proc/loadavg) T1=$(date +%s)
COMMIT=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
CPU=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)

python3 - "$TMP/section.md" "$TMP/rows" "$TMP/left_out" "$TMP/not_measured" "$SIZE" "$SAMPLES" "$EEVEE" "$COMMIT" "$(nproc)" "$CPU" \
    "$LOAD0" "$LOAD1" "$(( (T1 - T0 + 30) / 60 ))" "$REUSED" <<'PY'
import json, sys, datetime
out, rows_path, left_path, skipped_path, size, samples, eevee, commit, cores, cpu, load0, load1, minutes, reused = sys.argv[1:15]
FACTOR = 20  # the issue's figure: error no worse than EEVEE's at a frame time at least 20x shorter

def verdict(s_err, s_ms, ee, key):
    """Against each EEVEE render: is shadelab's error (key) no worse, at a frame >= 20x shorter?"""
    met, not_met = [], []
    for e in ee:
        err = e["interiors"][key]
        x = e["ms"] / s_ms
        if s_err <= err and x >= FACTOR:
            met.append("%d" % e["samples"])
        else:
            why = []
            if s_err > err: why.append("error %.3f > %.3f" % (s_err, err))
            if x < FACTOR: why.append("%.0f× faster" % x)
            not_met.append("%d: %s" % (e["samples"], ", ".join(why)))
    return met, not_met

def describe(met, not_met):
    if not not_met: return "**met** (EEVEE %s)" % ", ".join(met)
    if not met: return "not met (EEVEE %s)" % "; ".join(not_met)
    return "met against EEVEE %s; not against %s" % (", ".join(met), "; ".join(not_met))

rows, tally, scene_met = [], {}, {}
scene_eevee = {}
for line in open(rows_path).read().splitlines():
    scene, kind, path, args = line.split("|", 3)
    r = json.load(open(path))
    if r.get("eevee"): scene_eevee[scene] = r["eevee"]
    ee = scene_eevee.get(scene, [])
    setting = " ".join(a for a in args.split() if a != "--set")
    s_err, s_flip, s_ms = r["interiors"]["rel_rms"], r["interiors"].get("flip", -1), r["shadelab_ms"]
    first = kind == "defaults"
    ee_err = ", ".join("%.3f / %.3f (%d)" % (e["interiors"]["rel_rms"], e["interiors"].get("flip", -1), e["samples"])
                       for e in ee) if first else "as above"
    ee_ms = ", ".join("%.0f (%d)" % (e["ms"], e["samples"]) for e in ee) if first else "as above"
    # EEVEE's time at the fewest samples whose relative RMS is at most shadelab's, over shadelab's frame
    match = [e for e in ee if e["interiors"]["rel_rms"] <= s_err]
    if match: ratio = "%.0f× (EEVEE %d)" % (match[0]["ms"] / s_ms, match[0]["samples"])
    elif ee: ratio = "> %.0f× (EEVEE never as close)" % (ee[-1]["ms"] / s_ms)
    else: ratio = "-"
    fig = "-"
    if ee:
        m_rms, n_rms = verdict(s_err, s_ms, ee, "rel_rms")
        m_flip, n_flip = verdict(s_flip, s_ms, ee, "flip")
        fig = "rel-RMS: %s; FLIP: %s" % (describe(m_rms, n_rms), describe(m_flip, n_flip))
        t = tally.setdefault(kind, [0, 0, 0, 0])
        t[0] += not n_rms; t[1] += not n_flip; t[2] += not n_rms and not n_flip; t[3] += 1
        scene_met[scene] = scene_met.get(scene, False) or (not n_rms and not n_flip)
    rows.append("| `%s` | %s | %s | %.3f / %.3f (%.2f) | %s | %.1f | %s | %s | %s |" % (
        scene, r.get("plugins") or "none", "`%s`" % setting if not first else "defaults", s_err, s_flip,
        r["interiors"]["mean_ratio"], ee_err, s_ms, ee_ms, ratio, fig))
left = [l.split("|", 1) for l in open(left_path).read().splitlines()]
now = datetime.datetime.utcnow().strftime("%Y-%m-%d %H:%M UTC")
with open(out, "w") as f:
    f.write("<!-- xcheck-table begin: generated by tools/xcheck/xcheck-table.sh; do not edit by hand -->\n")
    f.write("## Against Cycles: shadelab and EEVEE\n\n")
    f.write("Generated by `tools/xcheck/xcheck-table.sh` (`shadelab-xcheck --size %s --samples %s [--eevee %s] "
            "[--set …] SCENE` per row) on %s at commit %s, %s cores (%s); load average %s at the start and %s at "
            "the end, %s min in all%s. Rows: every bundled scene Cycles can represent (the exporter lists nothing "
            "but tone mapping left out) at its defaults, then at each of its plugins' highest settings "
            "(`core.ssaa=4`; envmap's fis 32 with convolved irradiance and screen-space reflections; spotlight-shadow's PCSS at 4096² with 64 "
            "taps; bounce's 32² virtual lights a map and 24 probes along the scene; aa, ggx and normal-map are at their highest by default), then with the screen-space effects "
            "EEVEE renders with (its ambient occlusion and screen-space reflections): the ssao plugin loaded "
            "and, where envmap is, `envmap.reflections=screen`. Error: relative RMS / FLIP "
            "against a %s-sample Cycles reference over every object's interior and the background "
            "(silhouettes left out), before tone mapping (FLIP: LDR-FLIP with both images at one exposure, "
            "Cycles' 99th-percentile luminance at 1), and shadelab's mean ratio; the reference's own noise "
            "is part of every figure. shadelab: its still (the frames TAA averages, at least 8), the median frame time, llvmpipe. EEVEE: "
            "Blender's real-time renderer on the same llvmpipe under Xvfb, one render of N samples after a "
            "one-sample render that compiles its shaders, once per scene. *EEVEE's time at shadelab's error*: "
            "EEVEE's time at the fewest samples whose relative RMS is at most shadelab's, over shadelab's "
            "frame. *The target*: shadelab's error no worse than EEVEE's at a frame at least %d× "
            "shorter, judged against each EEVEE render ([docs/xcheck.md](xcheck.md)).\n\n"
            % (size, samples, eevee, now, commit, cores, cpu, load0, load1, minutes,
               " (%s rows kept from an interrupted run of the same command, REUSE=1)" % reused if int(reused) else "",
               samples, FACTOR))
    f.write("| scene | plugins | setting | shadelab rel-RMS / FLIP (mean ratio) | EEVEE rel-RMS / FLIP (samples) | "
            "shadelab ms/frame | EEVEE ms/render (samples) | EEVEE's time at shadelab's error | the target |\n"
            "|---|---|---|---|---|---|---|---|---|\n")
    f.write("\n".join(rows) + "\n\n")
    kinds = {"defaults": "at the defaults", "highest": "at the highest settings",
             "effects": "with EEVEE's screen-space effects"}
    for k, (rms, flip, both, n) in tally.items():
        f.write("The target %s: met against every EEVEE render on %d of %d rows by relative RMS, "
                "%d by FLIP, %d by both.\n" % (kinds[k], rms, n, flip, both))
    missed = sorted(s for s, ok in scene_met.items() if not ok)
    f.write("Per scene, at one of its rows at least: met by both on %d of %d scenes%s.\n"
            % (len(scene_met) - len(missed), len(scene_met),
               "; not on %s" % ", ".join("`%s`" % s for s in missed) if missed else ""))
    if left:
        f.write("\nLeft out (the exporter's reason): %s.\n" % "; ".join("`%s`: %s" % (s, why) for s, why in left))
    skipped = open(skipped_path).read().splitlines()
    if skipped:
        f.write("\nNot measured in this run (its time limit, LIMIT_MIN): %s.\n" % "; ".join(skipped))
    f.write("<!-- xcheck-table end -->\n")
PY
if [ "$OUT" = - ]; then cat "$TMP/section.md"; exit 0; fi
python3 - "$OUT" "$TMP/section.md" <<'PY'
import sys, re
path, section = sys.argv[1], open(sys.argv[2]).read()
try:
    text = open(path).read()
except FileNotFoundError:
    text = ""
pattern = re.compile(r"<!-- xcheck-table begin.*?<!-- xcheck-table end -->\n?", re.S)
text = pattern.sub(lambda m: section, text) if pattern.search(text) else text.rstrip("\n") + "\n\n" + section
open(path, "w").write(text)
PY
note "wrote $OUT"
