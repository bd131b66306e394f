#!/usr/bin/env bash
# The lobe contract's fallback warning (sdk/docs/plugin-guide.md, "Lobes"): a shading model
# without MODEL_LOBES that an environment or an area light lights is named in one warning line at
# start (model and plugin), once per run however many materials use it; models with lobes and
# scenes without such lights give none. The models without lobes: classic phong (phong), skin
# (sss), dielectric (extras/refraction).
#   usage: lobes_fallback.sh VIEWER TMPDIR
set -euo pipefail
VIEWER=$1 T=$2
fail() { echo "FAIL: $*"; exit 1; }
scene() { # scene FILE PLUGINS MATERIALS LIGHTS ENVIRONMENT
  local nodes="" i=0 m
  for m in $(sed -n 's/.*"name": "\([^"]*\)".*/\1/p' <<<"$3" | tr '\n' ' '); do
    nodes+="${nodes:+, }{\"name\": \"n$i\", \"translate\": [$((i * 2 - 6)), 0, 0], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.8}, \"material\": \"$m\"}"
    i=$((i + 1))
  done
  cat >"$1" <<JSON
{"plugins": [$2], "params": {"sss.ts_size": 64, "sss.cache": false},
 "cameras": [{"name": "c", "position": [0, 2, 12], "target": [0, 0, 0], "fov_y": 50}],
 "materials": [
$3
 ],
 "nodes": [$nodes],
 "lights": [$4], "environment": $5}
JSON
}
warnings() { grep -c "describes no lobes" "$1" || true; }
count_for() { grep -c "shading model \"$2\" (plugin $3) describes no lobes (MODEL_LOBES)" "$1" || true; }
render() { # render SCENE LOG
  "$VIEWER" --headless --size 64x32 --scene "$1" --output "$T/out.png" 2>"$2" || { cat "$2"; fail "render $1"; }
}
materials='  {"name": "phong1", "model": "phong", "base_color": [0.8, 0.5, 0.3]},
  {"name": "phong2", "model": "phong", "base_color": [0.3, 0.5, 0.8]},
  {"name": "skin", "model": "skin", "base_color": [0.62, 0.38, 0.3]},
  {"name": "glass", "model": "dielectric", "ior": 1.5},
  {"name": "gloss", "model": "blinn-gloss", "base_color": [0.5, 0.5, 0.5]},
  {"name": "metal", "model": "ggx", "base_color": [0.9, 0.8, 0.5], "roughness": 0.3},
  {"name": "plain", "model": "lambert", "base_color": [0.7, 0.7, 0.7]}'
point='{"name": "p", "type": "point", "position": [0, 4, 6], "intensity": 40}'

echo "== envmap lights every model: one warning per model without lobes"
scene "$T/env.json" '"envmap", "phong", "sss", "refraction", "ggx"' "$materials" "$point" '{"intensity": 1}'
render "$T/env.json" "$T/env.log"
grep "describes no lobes" "$T/env.log" || true
for m in "phong phong" "skin sss" "dielectric refraction"; do
  set -- $m
  n=$(count_for "$T/env.log" "$1" "$2")
  [ "$n" = 1 ] || fail "model $1 (plugin $2): $n warning lines, expected 1"
done
[ "$(warnings "$T/env.log")" = 3 ] || fail "models with lobes (blinn-gloss, ggx, lambert) were warned about"

echo "== an area light: the same for the models it lights"
scene "$T/area.json" '"area-light", "phong", "sss", "ggx"' "$(grep -v dielectric <<<"$materials")" \
  "$point, {\"name\": \"a\", \"type\": \"area\", \"position\": [0, 4, 4], \"direction\": [0, -0.7, -0.7], \"intensity\": 5, \"width\": 2, \"height\": 1, \"axis\": [1, 0, 0]}" \
  '{"color": [0.1, 0.1, 0.1]}'
render "$T/area.json" "$T/area.log"
[ "$(count_for "$T/area.log" phong phong)" = 1 ] && [ "$(count_for "$T/area.log" skin sss)" = 1 ] && \
  [ "$(warnings "$T/area.log")" = 2 ] || { cat "$T/area.log"; fail "area light: one warning each for phong and skin"; }

echo "== point lights only: nothing to warn about"
scene "$T/point.json" '"phong", "sss", "ggx"' "$(grep -v dielectric <<<"$materials")" "$point" '{"color": [0.1, 0.1, 0.1]}'
render "$T/point.json" "$T/point.log"
[ "$(warnings "$T/point.log")" = 0 ] || { cat "$T/point.log"; fail "a warning without an environment or area light"; }
echo "lobes_fallback: one warning line per model without lobes, only where an integrator lights it"
