#!/usr/bin/env bash
# A warm start compiles nothing the start before it compiled (issue 18 item 5: the warm start).
# llvmpipe compiles a program once per draw state (framebuffer formats, blend and depth, the state
# of every texture unit it samples), and Mesa's disk cache keeps each compile under a key made of
# that state and the program. A state that differs from run to run, or a program drawn in two
# states (llvmpipe hashes the second state's key over IR the first compile changed, which a warm
# start's cache hit does not change), made every warm start, or the first one, compile again:
# envmap's cached cube had other wrap modes than a prefiltered one, sss's blur left a unit empty
# and drew one program into two kinds of target, TAA drew its copy program into two. Counted as
# files in a fresh Mesa cache directory (with a fresh shadelab cache beside it): the second and the
# third start of the same command add none. Scenes that need no data files: the built-in default
# (envmap, shadows, normal map, tone mapping, TAA), the bare scene, and sss in texture space.
#   usage: cli_warm_start.sh SHADELAB SCENES_DIR OUTDIR
set -u
exe=$1 scenes=$2 out=$3
mkdir -p "$out"
. "$(dirname "$0")/cli_check.sh"
unset MESA_SHADER_CACHE_DISABLE MESA_GLSL_CACHE_DISABLE
entries() { find "$1/mesa" -type f ! -name index | wc -l; }
starts() { # starts NAME ARGS...: three starts on one pair of caches; the entry counts after each
    local name=$1 dir="$out/$1"
    shift
    mkdir -p "$dir/mesa"
    local counts=()
    for i in 1 2 3; do
        MESA_SHADER_CACHE_DIR="$dir/mesa" SHADELAB_CACHE="$dir" "$exe" --headless -q --size 64x36 --frames 3 \
            --output "$dir/out.png" "$@" || { echo "FAILED: $name: start $i failed"; fail=$((fail+1)); return; }
        counts+=("$(entries "$dir")")
    done
    echo "$name: Mesa cache entries after starts 1, 2, 3: ${counts[*]}"
    check test "${counts[0]}" -gt 0
    check test "${counts[1]}" -eq "${counts[0]}"
    check test "${counts[2]}" -eq "${counts[0]}"
}
starts default
starts basic --scene "$scenes/basic.json"
starts sss --scene "$scenes/skin_standin.json"
echo "cli_warm_start: $pass passed, $fail failed"
[ $fail -eq 0 ]
