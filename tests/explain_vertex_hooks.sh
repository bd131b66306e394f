#!/usr/bin/env bash
# --explain names a material's vertex hooks (tp-good's tp_vertex, gated on tp_lift) beside its
# fragment chunks, and a material without the key gets none.   usage: explain_vertex_hooks.sh SHADELAB
set -uo pipefail
T=$(mktemp -d "${TMPDIR:-/tmp}/shadelab-explain.XXXXXX")
trap 'rm -rf "$T"' EXIT
cat > "$T/scene.json" <<'JSON'
{"plugins": ["tp-good"],
 "materials": [{"name": "lifted", "tp_lift": 0.5}, {"name": "plain"}],
 "nodes": [{"name": "a", "mesh": {"primitive": "sphere"}, "material": "lifted"},
           {"name": "b", "translate": [2, 0, 0], "mesh": {"primitive": "sphere"}, "material": "plain"}],
 "lights": [{"name": "sun", "type": "directional"}]}
JSON
out=$("$1" --headless --size 32x32 --explain --scene "$T/scene.json" --output "$T/x.png" 2>&1) || { echo "$out"; exit 1; }
echo "$out" | grep -E '^ *(lifted|plain)'
echo "$out" | grep -E 'lifted' | grep -q 'tp-good:tp_vertex (vertex)' || { echo "FAIL: no vertex hook listed for lifted"; exit 1; }
if echo "$out" | grep -E 'plain' | grep -q 'tp_vertex'; then echo "FAIL: plain lists a vertex hook it does not have"; exit 1; fi
echo "ok"
