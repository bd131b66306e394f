# Sourced by the SDK tests: sl_install_prefix BUILD_DIR PREFIX WORK_DIR CMAKE
# Installs the build tree BUILD_DIR into PREFIX as `cmake --install` does. `cmake --install` runs
# BUILD/cmake_install.cmake, which also writes install_manifest.txt into the build tree; a
# read-only build tree cannot take that, so the same script runs from a copy whose manifest goes
# to WORK_DIR (the build tree's own install when the script's form is unknown).
sl_install_prefix() {
  local build=$1 pfx=$2 work=$3 cmake=$4 script moved
  script=$(<"$build/cmake_install.cmake")
  moved=${script//"file(WRITE \"$build/"/"file(WRITE \"$work/"}
  if [ "$moved" != "$script" ]; then
    printf '%s\n' "$moved" >"$work/cmake_install.cmake"
    "$cmake" -DCMAKE_INSTALL_PREFIX="$pfx" -P "$work/cmake_install.cmake" >"$work/install.log" 2>&1 \
      || { cat "$work/install.log"; echo "FAIL: install"; return 1; }
  else
    "$cmake" --install "$build" --prefix "$pfx" >"$work/install.log" \
      || { cat "$work/install.log"; echo "FAIL: install"; return 1; }
  fi
}
