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
# host->compile_ahead (ABI 1.12; sss's texture-space blur calls it): the forward programs drawn
# ahead under an empty scissor must be compiled for the very state the forward pass draws them
# with, or the forward pass compiles them again (one more variant: one more cache entry). A cold
# start with it and one without (SHADELAB_NO_COMPILE_AHEAD=1) compile as many variants and give
# the same image.
ahead() { # ahead NAME [ENV...]: one cold start; prints its Mesa cache entry count
    local dir="$out/$1"
    shift
    rm -rf "$dir" && mkdir -p "$dir/mesa"
    env "$@" MESA_SHADER_CACHE_DIR="$dir/mesa" SHADELAB_CACHE="$dir" "$exe" --headless -q --size 64x36 --frames 1 \
        --scene "$scenes/skin_standin.json" --set sss.method=texture-space $extra --output "$dir/out.png" >/dev/null 2>&1 &&
        entries "$dir"
}
extra=
with=$(ahead ahead_on) without=$(ahead ahead_off SHADELAB_NO_COMPILE_AHEAD=1)
echo "compile ahead: Mesa cache entries with $with, without $without"
check test -n "$with"
check test "$with" = "$without"
check cmp "$out/ahead_on/out.png" "$out/ahead_off/out.png"
# The same with envmap: the GGX material's forward program samples envmap's chain (the scene's
# constant environment), queued by the envmap-prefilter pass after the shadow maps and compiled
# ahead while it may still be prefiltering.
extra="--plugin envmap"
with=$(ahead ahead_env_on) without=$(ahead ahead_env_off SHADELAB_NO_COMPILE_AHEAD=1)
echo "compile ahead under envmap: Mesa cache entries with $with, without $without"
check test -n "$with"
check test "$with" = "$without"
check cmp "$out/ahead_env_on/out.png" "$out/ahead_env_off/out.png"
# The huge-page re-exec (core/startup.c: glibc's malloc on transparent huge pages; made where
# 4 KiB page faults are slow, forced here with SHADELAB_HUGE_PAGES=1) keeps the process's name:
# exec'd through /proc/self/exe it was "exe" in ps, top and pkill.
if grep -qE '\[(always|madvise)\]' /sys/kernel/mm/transparent_hugepage/enabled 2>/dev/null; then
  env -u GLIBC_TUNABLES -u SHADELAB_SMALL_PAGES SHADELAB_HUGE_PAGES=1 "$exe" --headless -q --size 16x16 --frames 100000 --output "$out/name.png" &
  pid=$! name= reexec=
  for _ in $(seq 100); do # until the re-executed process runs (its environment has the tunable)
    if tr '\0' '\n' < /proc/$pid/environ 2>/dev/null | grep -q 'glibc.malloc.hugetlb=1'; then
      reexec=1 name=$(cat /proc/$pid/comm); break
    fi
    sleep 0.05
  done
  kill $pid 2>/dev/null; wait $pid 2>/dev/null
  echo "huge-page re-exec: ${reexec:-not seen}, process name '$name'"
  check test -n "$reexec"
  check test "$name" = "$(basename "$exe" | cut -c1-15)"
fi
echo "cli_warm_start: $pass passed, $fail failed"
[ $fail -eq 0 ]
