#!/usr/bin/env bash
# Installs every build/test dependency of shadelab from Debian 12's packages, only when missing.
# Nothing is downloaded from anywhere else. Safe to run repeatedly.
#   --with-tests  also what only the tests need: Blender (the cross-check's reference renderer,
#                 tools/xcheck, ctest -L xcheck), left out of the first command's install
set -euo pipefail

WITH_TESTS=0
for a in "$@"; do
  case "$a" in
    --with-tests) WITH_TESTS=1 ;;
    *) echo "install-deps: unknown option $a (expected --with-tests)" >&2; exit 2 ;;
  esac
done

PKGS=(
  build-essential cmake pkg-config
  libglfw3-dev            # window + input
  libosmesa6-dev          # headless CPU GL (llvmpipe)
  libegl-dev libegl1-mesa-dev libgl-dev libgles-dev mesa-common-dev libgbm-dev
  libgl1-mesa-dri         # llvmpipe/DRI drivers used by OSMesa and EGL surfaceless
  libopenimageio-dev openimageio-tools  # images in and out, image compare
  libpng-dev              # PNG output without loading OpenImageIO (core/image/image.c)
  libjpeg-dev libopenexr-dev  # native JPEG and EXR decoding (core/image/image_native.c; OpenEXRCore only)
  libcjson-dev            # JSON scenes
  libassimp-dev           # meshes other than glTF and OBJ (PLY, FBX, Collada, …)
  libmeshoptimizer-dev    # glTF EXT_meshopt_compression
  libdraco-dev            # glTF KHR_draco_mesh_compression (a module: core/scene/gltf_draco.cpp)
  assimp-testmodels       # test data: Debian's glTF2 sample models (ctest gltf_models), so it never skips
  libcglm-dev             # vector/matrix math
  libimgui-dev            # GUI (C++ adapter only)
  gnuplot-nox             # benchmark charts
  jq                      # tools/gallery.sh reads the scenes' gallery metadata
  xvfb xauth              # GUI smoke test
  clang libclang-rt-14-dev  # fuzzing (libFuzzer) and sanitizers
)
if [ "$WITH_TESTS" = 1 ]; then
  PKGS+=(blender          # shadelab-xcheck's reference (Cycles) and its tests; large, tests only
         python3-numpy)   # Blender's glTF importer needs it (the blender package does not depend on it)
fi

missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all dependencies present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
