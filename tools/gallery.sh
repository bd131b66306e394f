#!/usr/bin/env bash
# The gallery (docs/gallery.md), made from the scenes' own metadata; this script names no scene
# and no plugin. For each scene the project ships — every JSON file in a folder named scenes/,
# test data and build trees aside (scenes/, then the extras' and the SDK examples' scenes/):
#   - one image, captioned with the first sentence of the scene's "comment";
#   - one more per entry of its "gallery" array, {"caption": "…", "args": ["--set", "…", …]}:
#     the same scene with those command-line arguments (a debug view, a plugin switched off);
#   - scenes/default.json is the built-in default and is rendered without --scene.
# Then, per plugin (each folder with a CMakeLists.txt in plugins/, extras/ or sdk/example/),
# links to the images of the scenes that name it.
# A scene is skipped, with the reason in the gallery, when a plugin it names cannot be loaded
# (an extra not built) or a file it names is missing (the data directory, SHADELAB_DATA or
# ../shared/assets, or a generated file its "generated_by" names). Images are 320x180 PNG in
# docs/gallery/, rendered headless. Needs jq.
#   usage: tools/gallery.sh [BUILD_DIR] [OUT_DIR]   (defaults: build, docs)
#          tools/gallery.sh --plan [BUILD_DIR]     check the metadata and print what would be
#                                                  rendered, rendering nothing (test gallery_plan)
set -uo pipefail
plan=false
if [ "${1:-}" = --plan ]; then plan=true; shift; fi
root=$(cd "$(dirname "$0")/.." && pwd)
command -v jq >/dev/null || { echo "gallery.sh: needs jq (apt-get install jq)" >&2; exit 1; }
build=$(cd "${1:-$root/build}" && pwd) || { echo "gallery.sh: no build directory ${1:-$root/build}" >&2; exit 1; }
out=${2:-$root/docs}
exe=$build/shadelab
[ -x "$exe" ] || { echo "gallery.sh: $exe not built (./build.sh)" >&2; exit 1; }
[ -z "${SHADELAB_DATA:-}" ] && [ -d "$root/../shared/assets" ] && export SHADELAB_DATA=$(cd "$root/../shared/assets" && pwd)
size=${GALLERY_SIZE:-320x180}
md=$out/gallery.md
fails=0
declare -A loadable=()      # plugin id -> yes/no
declare -A shown_by=()      # plugin id -> markdown links to the images of scenes naming it
declare -A skipped_for=()   # plugin id -> a scene naming it was skipped
declare -A used=()          # image names given out

# The "gallery" entries must be {"caption": string, "args": [string, …]}.
valid_metadata() {
    jq -e '(.gallery // []) | type == "array" and all(.[]; type == "object" and (.caption | type) == "string"
           and (.args | type) == "array" and all(.args[]; type == "string"))' "$1" >/dev/null 2>&1
}

can_load() { # plugin id: loads with --strict (cached)
    local p=$1
    if [ -z "${loadable[$p]:-}" ]; then
        if "$exe" --headless --strict -q --list-plugins --scene "$root/scenes/basic.json" --plugin "$p" >/dev/null 2>&1
        then loadable[$p]=yes; else loadable[$p]=no; fi
    fi
    [ "${loadable[$p]}" = yes ]
}

missing_file() { # scene: prints the first file it names that exists neither beside it nor in the data directory
    local s=$1 dir f
    dir=$(dirname "$s")
    while IFS= read -r f; do
        [ -e "$dir/$f" ] || [ -e "$f" ] || { [ -n "${SHADELAB_DATA:-}" ] && [ -e "$SHADELAB_DATA/$f" ]; } || { echo "$f"; return; }
    done < <(jq -r '[.. | objects | to_entries[] | select(.key != "comment" and .key != "generated_by" and (.value | type) == "string") | .value
                     | select(test("\\.(jpe?g|png|tga|bmp|hdr|exr|glb|gltf|obj|fbx|ply|bin)$"; "i"))] | unique | .[]' "$s")
}

caption_of() { # the scene's "comment", first sentence (without a closing colon)
    jq -r '.comment // ""' "$1" | sed 's/\([.:]\) .*/\1/; s/:$//'
}

# render NAME CAPTION SCENE ARGS...: docs/gallery/NAME.png and a gallery.md entry with the
# command (paths relative to the repository, as a reader types them from its root)
render() {
    local name=$1 caption=$2 scene=$3; shift 3
    local args=("$@") p
    [ -n "$scene" ] && args=(--scene "$scene" "${args[@]}")
    if [ -n "${used[$name]:-}" ]; then
        echo "gallery.sh: two images would be named $name (${used[$name]} and ${scene:-the default scene})" >&2
        fails=$((fails + 1))
        return
    fi
    used[$name]=${scene:-the default scene}
    if $plan; then
        echo "$name: ${args[*]}"
        return
    fi
    local t0=$SECONDS
    if (cd "$root" && "$exe" --headless -q --size "$size" "${args[@]}" --output "$out/gallery/$name.png"); then
        printf '%-36s %3ds\n' "$name" $((SECONDS - t0)) >&2
        { echo "### $caption"
          echo
          echo "![$name](gallery/$name.png)"
          echo
          echo '```'
          echo "./build/shadelab --headless --size $size ${args[*]:+${args[*]} }--output $name.png"
          echo '```'
          echo; } >> "$md.tmp"
    else
        echo "gallery.sh: $name failed: $exe ${args[*]}" >&2
        fails=$((fails + 1))
        return 1
    fi
}

note() { $plan && echo "skip: $1" || { echo "### $1"; echo; } >> "$md.tmp"; }

if ! $plan; then
    mkdir -p "$out/gallery"
    { echo "# Gallery"
      echo
      echo "One image per scene the project ships (\`scenes/\`, the extras' and the SDK examples'), and more"
      echo "where a scene's \`gallery\` entry asks for them, $size, made by \`tools/gallery.sh\` from the"
      echo "scenes' own metadata (headless; re-run it after changing a scene or a plugin). Each image has"
      echo "the command that made it, run from the repository root."
      echo
      echo "## Scenes"
      echo; } > "$md.tmp"
fi

# Every shipped scene: JSON files in folders named scenes/, outside build trees, test data and
# nested checkouts; the built-in default first, then by depth (scenes/ before the modules' own)
# and path.
scenes=("$root/scenes/default.json")
while IFS= read -r s; do
    [ "$s" != "${scenes[0]}" ] && scenes+=("$s")
done < <(cd "$root" && find . \( -path './build*' -o -path '*/build-*' -o -path ./tests -o -path ./.git \
                                  -o -path ./shared \) -prune -o -path '*/scenes/*.json' -type f -printf '%d %P\n' |
             LC_ALL=C sort -k1,1n -k2 | sed "s|^[0-9]* |$root/|")
for s in "${scenes[@]}"; do
    rel=${s#"$root/"}
    stem=$(basename "$s" .json)
    # a module's scene (MODULE/scenes/NAME.json) is named MODULE-NAME
    [[ $rel == */scenes/* ]] && stem="$(basename "$(dirname "$(dirname "$s")")")-$stem"
    if ! valid_metadata "$s"; then
        echo "gallery.sh: $rel: \"gallery\" must be an array of {\"caption\": string, \"args\": [strings]}" >&2
        fails=$((fails + 1))
        continue
    fi
    mapfile -t plugins < <(jq -r '.plugins // [] | .[]' "$s")
    why=""
    for p in "${plugins[@]}"; do can_load "$p" || { why="needs plugin $p, which does not load here (built?)"; break; }; done
    if [ -z "$why" ] && f=$(missing_file "$s") && [ -n "$f" ]; then
        gen=$(jq -r '.generated_by // ""' "$s")
        if [ -n "$gen" ]; then why="needs $f, a generated file: run $gen"
        else why="needs $f (the data directory, --data or SHADELAB_DATA)"; fi
    fi
    if [ -n "$why" ]; then
        note "$rel — skipped: $why"
        for p in "${plugins[@]}"; do skipped_for[$p]=1; done
        continue
    fi
    if [ "$rel" = scenes/default.json ]; then
        name=default scene="" title="$rel, built in (no --scene)"
    else
        name="scene-$stem" scene=$rel title=$rel
    fi
    if render "$name" "$title — $(caption_of "$s")" "$scene"; then
        for p in "${plugins[@]}"; do shown_by[$p]+="${shown_by[$p]:+, }[$rel](gallery/$name.png)"; done
    fi
    count=$(jq '.gallery // [] | length' "$s")
    for ((k = 0; k < count; k++)); do
        mapfile -t extra < <(jq -r ".gallery[$k].args[]" "$s")
        render "$name-$((k + 1))" "$title — $(jq -r ".gallery[$k].caption" "$s")" "$scene" "${extra[@]}"
    done
done

if ! $plan; then
    { echo "## Plugins"
      echo
      echo "The scenes that name each plugin (\`\"plugins\"\`), linked to their images."
      echo
      for dir in "$root"/plugins/*/ "$root"/extras/*/ "$root"/sdk/example/*/; do
          [ -f "$dir/CMakeLists.txt" ] || continue
          p=$(basename "$dir")
          readme=${dir#"$root/"}README.md
          if [ -n "${shown_by[$p]:-}" ]; then echo "- [$p](../$readme): ${shown_by[$p]}"
          elif [ -n "${skipped_for[$p]:-}" ]; then echo "- [$p](../$readme): its scenes were skipped (above)"
          else echo "- [$p](../$readme): no scene names it"; fi
      done
      echo; } >> "$md.tmp"
    mv "$md.tmp" "$md"
    du -ch "$out"/gallery/*.png | tail -1 >&2
fi
[ $fails -eq 0 ]
