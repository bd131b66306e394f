#!/usr/bin/env bash
# Installs what is missing (Debian packages only), configures and builds shadelab into build/.
# Extra arguments are passed to the CMake configure step (e.g. -DSL_SANITIZE=ON).
set -euo pipefail
cd "$(dirname "$0")"
bash tools/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo "$@" > build-configure.log 2>&1 || { cat build-configure.log; exit 1; }
cmake --build build -j"$(nproc)"
