#!/usr/bin/env bash
# The gallery (docs/gallery.md): one small image per bundled scene (scenes/*.json) and one per
# bundled plugin (plugins/*/), each with the command that made it. Images are 320x180 PNG in
# docs/gallery/ (about 2 MB in all), rendered headless (OSMesa on this machine).
#   usage: tools/gallery.sh [BUILD_DIR] [OUT_DIR]      (defaults: build, docs)
# Scenes that need the data directory (head, shadow_head, skin_head) are rendered when
# SHADELAB_DATA or ../shared/assets has it, else listed as skipped. Re-running overwrites.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd) || { echo "gallery.sh: no build directory ${1:-$root/build}" >&2; exit 1; }
out=${2:-$root/docs}
exe=$build/shadelab
[ -x "$exe" ] || { echo "gallery.sh: $exe not built (./build.sh)" >&2; exit 1; }
[ -z "${SHADELAB_DATA:-}" ] && [ -d "$root/../shared/assets" ] && export SHADELAB_DATA=$(cd "$root/../shared/assets" && pwd)
size=${GALLERY_SIZE:-320x180}
mkdir -p "$out/gallery"
md=$out/gallery.md
fails=0

# render NAME CAPTION ARGS...: docs/gallery/NAME.png and a gallery.md entry with the command
# (paths relative to the repository, as a reader types them from its root)
render() {
    local name=$1 caption=$2; shift 2
    local t0=$SECONDS
    if (cd "$root" && "$exe" --headless -q --size $size "$@" --output "$out/gallery/$name.png"); then
        printf '%-28s %3ds\n' "$name" $((SECONDS - t0)) >&2
        { echo "### $caption"
          echo
          echo "![$name](gallery/$name.png)"
          echo
          echo '```'
          echo "./build/shadelab --headless --size $size ${*:+$* }--output $name.png"
          echo '```'
          echo; } >> "$md.tmp"
    else
        echo "gallery.sh: $name failed: $exe $*" >&2
        fails=$((fails + 1))
    fi
}

comment() { # the scene's "comment", first sentence
    sed -n 's/^ *"comment": *"\([^"]*\)".*/\1/p' "$1" | head -1 | sed 's/\([.:]\) .*/\1/'
}

{
echo "# Gallery"
echo
echo "One image per bundled scene and per bundled plugin, $size, made by \`tools/gallery.sh\`"
echo "(headless, OSMesa/llvmpipe; re-run it after changing a scene or a plugin). Each image has the"
echo "command that made it, run from the repository root (the head scenes read the data directory:"
echo "\`SHADELAB_DATA\` or \`--data ../shared/assets\`)."
echo
echo "## Scenes"
echo
} > "$md.tmp"

render default "The built-in default scene (no file): every bundled plugin together"
for s in "$root"/scenes/*.json; do
    name=$(basename "$s" .json)
    [ "$name" = default ] && continue
    if grep -q '"head/' "$s" && { [ -z "${SHADELAB_DATA:-}" ] || [ ! -d "$SHADELAB_DATA/head" ]; }; then
        { echo "### scenes/$name.json — skipped: needs the data directory (\`--data\`, head/)"; echo; } >> "$md.tmp"
        continue
    fi
    render "scene-$name" "scenes/$name.json — $(comment "$s")" --scene "scenes/$name.json"
done

{ echo "## Plugins"; echo; echo "Each on the built-in default scene unless a scene of its own shows it better."; echo; } >> "$md.tmp"
for dir in "$root"/plugins/*/; do
    p=$(basename "$dir")
    case $p in
    aa)    render plugin-aa "aa — antialiasing (TAA by default) on its edge scene; --set aa.enabled=false for the aliased image" \
               --scene scenes/aa_edges.json ;;
    envmap) render plugin-envmap "envmap — the procedural sky's image-based light alone (sun and spot off)" \
               --set light.sun.enabled=false --set light.spot.enabled=false ;;
    ggx)   render plugin-ggx "ggx — its debug view ggx-d: the GGX distribution D(h) of each material" --debug-view ggx-d ;;
    normal-map) render plugin-normal-map "normal-map — the world normal after the procedural waves map (final-normal)" \
               --debug-view final-normal ;;
    phong) render plugin-phong "phong — the gloss-map assignment: normalised Blinn-Phong, gloss and AO maps" \
               --scene scenes/gloss_ao.json ;;
    spotlight-shadow) render plugin-spotlight-shadow "spotlight-shadow — the shadowed sun and the spot light alone (the sky's light off)" \
               --set envmap.enabled=false ;;
    sss)   render plugin-sss "sss — subsurface scattering on the procedural skin stand-in" --scene scenes/skin_standin.json ;;
    tonemap) render plugin-tonemap "tonemap — false colour: exposure in stops around middle grey" --set tonemap.false_color=true ;;
    *)     echo "gallery.sh: plugin $p has no gallery entry: add one to tools/gallery.sh" >&2; fails=$((fails + 1)) ;;
    esac
done
mv "$md.tmp" "$md"
du -ch "$out"/gallery/*.png | tail -1 >&2
[ $fails -eq 0 ]
