#!/usr/bin/env bash
# Installs what is missing (Debian packages only), configures and builds shadelab into build/.
# --with-tests also installs what only the tests need (Blender, for the cross-check: the README's
# test command). Other arguments are passed to the CMake configure step (e.g. -DSL_SANITIZE=ON).
set -euo pipefail
cd "$(dirname "$0")"
deps=()
cmake_args=()
for a in "$@"; do
  if [ "$a" = --with-tests ]; then deps+=(--with-tests); else cmake_args+=("$a"); fi
done
bash tools/install-deps.sh "${deps[@]}"
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo "${cmake_args[@]}" > build-configure.log 2>&1 || { cat build-configure.log; exit 1; }
cmake --build build -j"$(nproc)"
