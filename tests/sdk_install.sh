#!/usr/bin/env bash
# SDK test: install shadelab into a temporary prefix, build sdk/example out of tree against it
# (find_package(shadelab) and pkg-config), run the example's own harness test, check that each
# of its features visibly changes the installed viewer's image, and that ABI-mismatched builds
# of the same example are refused with both versions named while the viewer goes on.
#   usage: sdk_install.sh SOURCE_DIR BUILD_DIR IMGDIFF [CMAKE]
set -euo pipefail
SRC=$1 BUILD=$2 IMGDIFF=$3 CMAKE=${4:-cmake}
T=$(mktemp -d "${TMPDIR:-/tmp}/shadelab-sdk.XXXXXX")
trap 'rm -rf "$T"' EXIT
PFX=$T/prefix
fail() { echo "FAIL: $*"; exit 1; }
step() { echo; echo "== $*"; }
export SHADELAB_PLUGIN_PATH= SHADELAB_SHADER_DIR=

step "cmake --install into $PFX"
. "$(dirname "$0")/sdk_prefix.sh"
sl_install_prefix "$BUILD" "$PFX" "$T" "$CMAKE" || fail "install"
for f in bin/shadelab include/shadelab/shadelab.h include/shadelab/harness.h lib*/cmake/shadelab/shadelabConfig.cmake \
         lib*/cmake/shadelab/ShadelabPlugin.cmake lib*/pkgconfig/shadelab.pc share/shadelab/shaders/common.glsl; do
  compgen -G "$PFX/$f" >/dev/null || fail "not installed: $f"
done
VIEWER=$PFX/bin/shadelab
# (output captured first: with pipefail, grep -q quitting early would SIGPIPE the writer)
grep -q "$PFX/bin/../lib.*/shadelab/plugins" <<<"$("$VIEWER" --list-plugins)" || fail "installed viewer does not search its plugin dir"

step "installed built-in plugins load by name"
for d in "$PFX"/lib*/shadelab/plugins/*/; do
  [ -d "$d" ] || continue
  name=$(basename "$d")
  "$VIEWER" --plugin "$name" --list-plugins 2>/dev/null | grep -E "^$name +(enabled|off) +$PFX" >/dev/null \
    || { "$VIEWER" --plugin "$name" --list-plugins; fail "installed plugin $name does not load by name"; }
  echo "  $name: loads from $d"
done

step "installed viewer renders like the build tree's"
"$VIEWER" --headless --size 160x90 --output "$T/installed.png" 2>/dev/null
"$BUILD/shadelab" --headless --size 160x90 --output "$T/build.png" 2>/dev/null
"$IMGDIFF" "$T/installed.png" "$T/build.png" --same 0
# ... and it really uses the installed shaders (not the source tree's): change the installed
# forward shader's output (every frame runs it; the display pass does not always run, ABI 1.8
# display_on_write), expect a different image, then restore it
FORWARD_FRAG=$PFX/share/shadelab/shaders/forward.frag
cp "$FORWARD_FRAG" "$T/forward.frag.orig"
sed -i 's/o_color = vec4(mix(c, /o_color = vec4(4.0 - mix(c, /' "$FORWARD_FRAG"
grep -q "o_color = vec4(4.0 - mix(c, " "$FORWARD_FRAG" || fail "could not patch the installed forward.frag (changed?)"
"$VIEWER" --headless --size 160x90 --output "$T/patched.png" 2>/dev/null
"$IMGDIFF" "$T/patched.png" "$T/build.png" --differ 0.2
cp "$T/forward.frag.orig" "$FORWARD_FRAG"

step "pkg-config: compile the example with \$(pkg-config --cflags shadelab) only"
export PKG_CONFIG_PATH=$(dirname "$(compgen -G "$PFX/lib*/pkgconfig/shadelab.pc")")
PCFLAGS=$(pkg-config --cflags shadelab)
echo "pkg-config --cflags shadelab: $PCFLAGS   abi $(pkg-config --variable=abi_major shadelab).$(pkg-config --variable=abi_minor shadelab)"
mkdir -p "$T/pc/example"
cc -std=c11 -shared -fPIC -fvisibility=hidden $PCFLAGS "$SRC/sdk/example/example.c" -o "$T/pc/example/example.so"
cp "$SRC/sdk/example/tint.glsl" "$SRC/sdk/example/vignette.frag" "$T/pc/example/"
grep -q " T shadelab_plugin_entry" <<<"$(nm -D --defined-only "$T/pc/example/example.so")" || fail "entry symbol not exported"
"$VIEWER" --headless --size 160x90 --strict --plugin "$T/pc/example/example.so" --output "$T/pc.png" 2>/dev/null

step "find_package(shadelab): configure, build and test sdk/example out of tree"
"$CMAKE" -S "$SRC/sdk/example" -B "$T/ex" -DCMAKE_PREFIX_PATH="$PFX" -DCMAKE_BUILD_TYPE=RelWithDebInfo >"$T/ex.log" \
  || { cat "$T/ex.log"; fail "configure"; }
"$CMAKE" --build "$T/ex" >>"$T/ex.log" 2>&1 || { cat "$T/ex.log"; fail "build"; }
PLUGIN=$T/ex/plugins/example/example.so
[ -f "$PLUGIN" ] && [ -e "$T/ex/plugins/example/tint.glsl" ] || fail "plugin layout"
(cd "$T/ex" && ctest --output-on-failure) || fail "the example's harness test"
"$VIEWER" --headless --size 160x90 --strict --plugin "$PLUGIN" --output "$T/cm.png" 2>/dev/null
"$IMGDIFF" "$T/pc.png" "$T/cm.png" --same 0                   # pkg-config build = CMake build

step "find_package(shadelab): the ssao example (depth, normals, pre-pass, pass views) out of tree"
"$CMAKE" -S "$SRC/sdk/example/ssao" -B "$T/ssao" -DCMAKE_PREFIX_PATH="$PFX" -DCMAKE_BUILD_TYPE=RelWithDebInfo >"$T/ssao.log" \
  && "$CMAKE" --build "$T/ssao" >>"$T/ssao.log" 2>&1 || { cat "$T/ssao.log"; fail "ssao: configure and build"; }
(cd "$T/ssao" && ctest --output-on-failure) || fail "the ssao example's harness test"

step "find_package(shadelab): the toon example (a model lit at the dominant light) out of tree"
"$CMAKE" -S "$SRC/sdk/example/toon" -B "$T/toon" -DCMAKE_PREFIX_PATH="$PFX" -DCMAKE_BUILD_TYPE=RelWithDebInfo >"$T/toon.log" \
  && "$CMAKE" --build "$T/toon" >>"$T/toon.log" 2>&1 || { cat "$T/toon.log"; fail "toon: configure and build"; }
(cd "$T/toon" && ctest --output-on-failure) || fail "the toon example's harness test"

step "each feature of the example visibly changes the image (installed viewer, --plugin PATH)"
r() { local out=$1; shift; "$VIEWER" --headless --size 160x90 --strict --plugin "$PLUGIN" "$@" --output "$out" 2>"$out.log" \
        || { cat "$out.log"; fail "render $out"; }; }
"$VIEWER" --headless --size 160x90 --output "$T/none.png" 2>/dev/null
r "$T/off.png" --set example.enabled=false
r "$T/param.png" --set example.vignette=false --set example.tint_strength=0.2
r "$T/hook.png" --set example.vignette=false
r "$T/pass.png" --set example.tint=false
r "$T/all.png"
"$IMGDIFF" "$T/off.png" "$T/none.png" --same 0                # loaded but off = not loaded
"$IMGDIFF" "$T/hook.png" "$T/off.png" --differ 0.02           # the SURFACE hook
"$IMGDIFF" "$T/pass.png" "$T/off.png" --differ 0.02           # the POST pass
"$IMGDIFF" "$T/param.png" "$T/hook.png" --differ 0.01         # the parameter (tint strength)
"$IMGDIFF" "$T/all.png" "$T/hook.png" --differ 0.02
"$IMGDIFF" "$T/all.png" "$T/pass.png" --differ 0.02
grep -q '"example.tint_strength"' <<<"$("$VIEWER" --plugin "$PLUGIN" --dump-params)" || fail "--dump-params lacks example.tint_strength"
grep -q "toggle the vignette" <<<"$("$VIEWER" --plugin "$PLUGIN" --help-keys)" || fail "--help-keys lacks the example's keys"

step "install the example into the prefix: the viewer finds it by name"
"$CMAKE" --install "$T/ex" --prefix "$PFX" >/dev/null
"$VIEWER" --plugin example --list-plugins | grep -E "^example +enabled" || fail "--plugin example not found by name"

step "ABI: refused with both versions named, the viewer goes on; --strict is fatal"
HOST_MAJOR=$(pkg-config --variable=abi_major shadelab) HOST_MINOR=$(pkg-config --variable=abi_minor shadelab)
check_refused() { # name, C flags, expected "plugin built for ABI X.Y"
  local name=$1 flags=$2 want=$3
  "$CMAKE" -S "$SRC/sdk/example" -B "$T/$name" -DCMAKE_PREFIX_PATH="$PFX" -DBUILD_TESTING=OFF "-DCMAKE_C_FLAGS=$flags" >"$T/$name.log" \
    && "$CMAKE" --build "$T/$name" >>"$T/$name.log" 2>&1 || { cat "$T/$name.log"; fail "$name build"; }
  local so=$T/$name/plugins/example/example.so
  local msg="ABI mismatch: plugin built for ABI $want, host provides ABI $HOST_MAJOR.$HOST_MINOR"
  rm -f "$T/$name.png"
  # the image is written and the run exits 2: it printed an error (docs: exit status)
  local rc=0
  "$VIEWER" --headless --size 160x90 --plugin "$so" --output "$T/$name.png" 2>"$T/$name.err" || rc=$?
  [ $rc -eq 2 ] || { cat "$T/$name.err"; fail "$name: viewer exited $rc, not 2 (image written, error printed)"; }
  grep -F "$msg" "$T/$name.err" || { cat "$T/$name.err"; fail "$name: no '$msg' on stderr"; }
  "$IMGDIFF" "$T/$name.png" "$T/none.png" --same 0   # rendered, without the plugin
  "$VIEWER" --plugin "$so" --list-plugins 2>/dev/null | grep -A2 "DISABLED" | grep -F "$msg" >/dev/null || fail "$name: --list-plugins lacks the reason"
  if "$VIEWER" --headless --size 160x90 --strict --plugin "$so" --output "$T/$name-strict.png" 2>"$T/$name.strict"; then
    fail "$name: --strict did not fail"
  fi
  grep -F "$msg" "$T/$name.strict" >/dev/null || fail "$name: --strict message lacks the versions"
  echo "$name: refused: $msg; --strict exits non-zero"
}
check_refused abi-major "-DSL_ABI_MAJOR=$((HOST_MAJOR + 1))" "$((HOST_MAJOR + 1)).$HOST_MINOR"
check_refused abi-minor "-DSL_ABI_MINOR=$((HOST_MINOR + 1))" "$HOST_MAJOR.$((HOST_MINOR + 1))"

echo; echo "PASS: SDK install, out-of-tree example, feature checks, ABI refusals"
