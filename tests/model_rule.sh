#!/usr/bin/env bash
# The model rule (issue 41; docs/design-notes.md, "Lobes: one lighting contract"): no plugin,
# extra or SDK example names a shading model it does not register. A chunk may test
# SL_MODEL_<NAME> only for models of its own module (registered with SL_HOOK_SHADING_MODEL in
# its C files); light integrators reach every other model through the lobe contract
# (sl_model_lobes). SL_MODEL_HAS_LOBES and SL_MODEL_MASKS_FACING_AWAY are the contract's own.
#   usage: tests/model_rule.sh SOURCE_DIR      exit 0 when it holds, 1 naming each offence
#          tests/model_rule.sh --self-test     checks that a planted offence is found
set -euo pipefail
if [ "${1:-}" = "--self-test" ]; then
  T=$(mktemp -d "${TMPDIR:-/tmp}/shadelab-model-rule.XXXXXX")
  trap 'rm -rf "$T"' EXIT
  mkdir -p "$T/plugins/a" "$T/plugins/b"
  printf 'C(.hook = SL_HOOK_SHADING_MODEL, .file = "a.glsl", .function = "f",\n  .name = "foo-bar"),\n' >"$T/plugins/a/a.c"
  printf '#if defined(SL_MODEL_FOO_BAR)\n#endif\n' >"$T/plugins/a/a.glsl"
  "$0" "$T" >/dev/null || { echo "model_rule self-test: a module naming its own model was refused"; exit 1; }
  printf '#if defined(SL_MODEL_FOO_BAR)\n#endif\n' >"$T/plugins/b/b.glsl"
  if "$0" "$T" >"$T/out"; then echo "model_rule self-test: SL_MODEL_FOO_BAR in plugins/b was not found"; exit 1; fi
  grep -q 'plugins/b/b.glsl:1' "$T/out" || { echo "model_rule self-test: the offence was not named"; cat "$T/out"; exit 1; }
  echo "model_rule self-test: a planted offence is found and named"
  exit 0
fi
if [ $# -ne 1 ]; then echo "usage: $0 SOURCE_DIR | --self-test" >&2; exit 2; fi
SRC=$(cd "$1" && pwd -P) || { echo "model_rule: no source directory $1" >&2; exit 2; }
bad=0
for m in "$SRC"/plugins/* "$SRC"/extras/* "$SRC"/sdk/example; do
  [ -d "$m" ] || continue
  # the models this module registers, as the composer spells their macros (shader.h)
  own=$(find "$m" -path '*/tests' -prune -o -name '*.c' -print | { xargs -r grep -h -A3 'SL_HOOK_SHADING_MODEL' || true; } |
        sed -n 's/.*\.name *= *"\([^"]*\)".*/\1/p' | tr 'a-z' 'A-Z' | sed 's/[^A-Z0-9]/_/g' | sort -u)
  while IFS=: read -r file line name; do
    case "$name" in SL_MODEL_HAS_LOBES | SL_MODEL_MASKS_FACING_AWAY) continue ;; esac
    if ! printf '%s\n' $own | grep -qx "${name#SL_MODEL_}"; then
      echo "${file#$SRC/}:$line: names $name, a model this module does not register (use the lobe contract, sl_model_lobes)"
      bad=1
    fi
  done < <(find "$m" -path '*/tests' -prune -o -type f \( -name '*.glsl' -o -name '*.frag' -o -name '*.vert' -o -name '*.c' -o -name '*.h' \) -print |
           xargs -r grep -HonE 'SL_MODEL_[A-Z0-9_]+' || true)
done
[ $bad = 0 ] && echo "model_rule: no plugin, extra or example names another module's shading model"
exit $bad
