#!/usr/bin/env bash
# The model rule (issue 41; docs/design-notes.md, "Lobes: one lighting contract"): no module names
# a shading model it does not register. A module — each plugin, extra, SDK example (sdk/example's
# own files, and each project under it), tool, and the core with its shader library — may test
# SL_MODEL_<NAME> only for models it registers (SL_HOOK_SHADING_MODEL in its C files); light
# integrators reach every other model through the lobe contract (sl_model_lobes).
# SL_MODEL_HAS_LOBES and SL_MODEL_MASKS_FACING_AWAY are the contract's own; tests/ is not a module.
#   usage: tests/model_rule.sh SOURCE_DIR      exit 0 when it holds, 1 naming each offence
#          tests/model_rule.sh --self-test     checks that planted offences are found
set -euo pipefail
if [ "${1:-}" = "--self-test" ]; then
  T=$(mktemp -d "${TMPDIR:-/tmp}/shadelab-model-rule.XXXXXX")
  trap 'rm -rf "$T"' EXIT
  mkdir -p "$T/plugins/a" "$T/plugins/b" "$T/sdk/example/x" "$T/sdk/example/y" "$T/core" "$T/shaders"
  printf 'C(.hook = SL_HOOK_SHADING_MODEL, .file = "a.glsl", .function = "f",\n  .name = "foo-bar"),\n' >"$T/plugins/a/a.c"
  printf '#if defined(SL_MODEL_FOO_BAR)\n#endif\n' >"$T/plugins/a/a.glsl"
  printf 'C(.hook = SL_HOOK_SHADING_MODEL, .file = "x.glsl", .function = "f", .name = "ex"),\n' >"$T/sdk/example/x/x.c"
  printf '#if defined(SL_MODEL_EX)\n#endif\n' >"$T/sdk/example/x/x.glsl"
  "$0" "$T" >"$T/out" || { echo "model_rule self-test: a module naming its own model was refused"; cat "$T/out"; exit 1; }
  planted=("plugins/b/b.glsl:SL_MODEL_FOO_BAR" "sdk/example/y/y.glsl:SL_MODEL_EX" "sdk/example/top.glsl:SL_MODEL_EX"
           "shaders/lib.glsl:SL_MODEL_FOO_BAR" "core/render.c:SL_MODEL_EX")
  for p in "${planted[@]}"; do
    file=${p%%:*} name=${p#*:}
    mkdir -p "$(dirname "$T/$file")"
    printf '#if defined(%s)\n#endif\n' "$name" >"$T/$file"
    if "$0" "$T" >"$T/out"; then echo "model_rule self-test: $name in $file was not found"; exit 1; fi
    grep -q "$file:1" "$T/out" || { echo "model_rule self-test: the offence in $file was not named"; cat "$T/out"; exit 1; }
    rm "$T/$file"
  done
  echo "model_rule self-test: planted offences in a plugin, an SDK example, the core and its shaders are found and named"
  exit 0
fi
if [ $# -ne 1 ]; then echo "usage: $0 SOURCE_DIR | --self-test" >&2; exit 2; fi
SRC=$(cd "$1" && pwd -P) || { echo "model_rule: no source directory $1" >&2; exit 2; }
bad=0
# check DEPTH DIR...: the files under the DIRs as one module (DEPTH: find -maxdepth, "" for all)
check() {
  local depth=$1; shift
  local limit=()
  [ -n "$depth" ] && limit=(-maxdepth "$depth")
  # the models this module registers, as the composer spells their macros (shader.h)
  local own
  own=$(find "$@" "${limit[@]}" -path '*/tests' -prune -o -name '*.c' -print | { xargs -r grep -h -A3 'SL_HOOK_SHADING_MODEL' || true; } |
        sed -n 's/.*\.name *= *"\([^"]*\)".*/\1/p' | tr 'a-z' 'A-Z' | sed 's/[^A-Z0-9]/_/g' | sort -u)
  while IFS=: read -r file line name; do
    case "$name" in SL_MODEL_HAS_LOBES | SL_MODEL_MASKS_FACING_AWAY) continue ;; esac
    if ! printf '%s\n' $own | grep -qx "${name#SL_MODEL_}"; then
      echo "${file#$SRC/}:$line: names $name, a model this module does not register (use the lobe contract, sl_model_lobes)"
      bad=1
    fi
  done < <(find "$@" "${limit[@]}" -path '*/tests' -prune -o -type f \
             \( -name '*.glsl' -o -name '*.frag' -o -name '*.vert' -o -name '*.c' -o -name '*.h' -o -name '*.cpp' \) -print |
           { xargs -r grep -HonE 'SL_MODEL_[A-Z0-9_]+' || true; })
}
for m in "$SRC"/plugins/* "$SRC"/extras/* "$SRC"/sdk/example/* "$SRC"/tools/*; do
  [ -d "$m" ] && check "" "$m"
done
[ -d "$SRC/sdk/example" ] && check 1 "$SRC/sdk/example"
core=()
for d in "$SRC/core" "$SRC/shaders"; do [ -d "$d" ] && core+=("$d"); done
[ ${#core[@]} -gt 0 ] && check "" "${core[@]}"
[ $bad = 0 ] && echo "model_rule: no module (plugin, extra, SDK example, tool, core) names another module's shading model"
exit $bad
