#!/usr/bin/env bash
# Lazy program creation (issue 19's cold start, docs/design-notes.md): a stand-alone program
# (the core's display/accumulate/resolve, a plugin's load_program) compiles when a pass first
# asks for its id, so programs of passes that never run are never compiled. Checked on the
# `-v` list of programs built: the bare scene with TAA builds, for one frame, TAA's copy program
# only (a frame without a history is copied as it is: no resolve), for two frames taa.frag too,
# and never fxaa.frag nor the core's display/accumulate/resolve (no window, no --accumulate, no
# supersampling); with
# aa.method=fxaa the other way round; with core.ssaa=2 and --accumulate 2 the resolve and accumulate programs are built. Whether a
# lazily built program gives the same frame as one built up front is the toggle matrix's job
# (tests/test_toggle_matrix.c switches aa's method and every plugin live).
#   usage: cli_lazy_programs.sh SHADELAB SCENES_DIR OUTDIR
set -u
exe=$1 scenes=$2 out=$3
mkdir -p "$out"
. "$(dirname "$0")/cli_check.sh"
built() { grep -F "built program" <<<"$1" | grep -qF "$2"; }
not_built() { ! built "$@"; }
msg=$("$exe" --headless -v --size 32x18 --scene "$scenes/basic.json" --frames 1 --output "$out/taa.png" 2>&1)
check test $? -eq 0
check built "$msg" taa_copy.frag
for p in taa.frag fxaa.frag sl:display.frag sl:accumulate.frag sl:resolve.frag; do check not_built "$msg" "$p"; done
msg=$("$exe" --headless -v --size 32x18 --scene "$scenes/basic.json" --frames 2 --output "$out/taa2.png" 2>&1)
check test $? -eq 0
check built "$msg" taa.frag
for p in fxaa.frag sl:display.frag sl:accumulate.frag sl:resolve.frag; do check not_built "$msg" "$p"; done
msg=$("$exe" --headless -v --size 32x18 --scene "$scenes/basic.json" --set aa.method=fxaa --frames 1 --output "$out/fxaa.png" 2>&1)
check test $? -eq 0
check built "$msg" fxaa.frag
check not_built "$msg" taa.frag
check not_built "$msg" taa_copy.frag
msg=$("$exe" --headless -v --size 32x18 --scene "$scenes/basic.json" --set core.ssaa=2 --accumulate 2 --frames 1 --output "$out/ssaa.png" 2>&1)
check test $? -eq 0
check built "$msg" sl:resolve.frag
check built "$msg" sl:accumulate.frag
# A plugin program that fails its first (lazy) compile disables the plugin, as a failing
# activate() does: the image equals the one with the plugin switched off (the frame is rendered
# again without it), and --strict makes the run fail. A copy of aa with taa.frag broken.
broken="$out/broken-plugins/aa"
mkdir -p "$broken"
cp -L "$(dirname "$exe")/plugins/aa/aa.so" "$broken/"
cp "$scenes/../plugins/aa/"*.frag "$scenes/../plugins/aa/"*.glsl "$broken/"
printf '\nvoid sl_broken() { no_such_function(); }\n' >> "$broken/taa.frag"
# The run writes its image and exits 2: it printed an error (one, naming the plugin and file).
msg=$(SHADELAB_PLUGIN_PATH="$out/broken-plugins" "$exe" --headless --size 32x18 --scene "$scenes/basic.json" --output "$out/broken.png" 2>&1)
check test $? -eq 2
check test -s "$out/broken.png"
check grep -qF "plugin aa disabled" <<<"$msg"
check grep -qF "taa.frag" <<<"$msg"
check test "$(grep -c '^error: ' <<<"$msg")" -eq 1
"$exe" --headless -q --size 32x18 --scene "$scenes/basic.json" --set aa.enabled=false --output "$out/aa-off.png"
check cmp -s "$out/broken.png" "$out/aa-off.png"
msg=$(SHADELAB_PLUGIN_PATH="$out/broken-plugins" "$exe" --headless --strict --size 32x18 --scene "$scenes/basic.json" --output "$out/broken-strict.png" 2>&1)
check test $? -ne 0
check grep -qF -- "--strict: plugin aa" <<<"$msg"
echo "cli_lazy_programs: $pass passed, $fail failed"
[ $fail -eq 0 ]
