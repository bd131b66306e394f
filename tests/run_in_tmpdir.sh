#!/usr/bin/env bash
# Runs a command-line test with a directory of its own for what it writes, never the build tree
# (which may be read-only or a copy).
#   usage: run_in_tmpdir.sh NAME COMMAND [ARGS...]
# Every "@TMP@" in ARGS becomes that directory, which is also the working directory:
# $SL_TEST_OUT/NAME when SL_TEST_OUT is set (kept), else a fresh mktemp -d directory under
# $TMPDIR (or /tmp), removed afterwards unless COMMAND failed and wrote something there (then
# kept, its path on stderr) or SL_TEST_KEEP=1. Exits with COMMAND's status.
set -u
name=$1; shift
if [ -n "${SL_TEST_OUT:-}" ]; then
  dir=$SL_TEST_OUT/$name
  mkdir -p "$dir" || exit 1
  temporary=0
else
  dir=$(mktemp -d "${TMPDIR:-/tmp}/shadelab-test-$name.XXXXXX") || exit 1
  temporary=1
fi
args=()
for a in "$@"; do args+=("${a//@TMP@/$dir}"); done
(cd "$dir" && "${args[@]}")
rc=$?
if [ $temporary = 1 ]; then
  if [ "${SL_TEST_KEEP:-0}" != 0 ] || { [ $rc != 0 ] && [ -n "$(ls -A "$dir")" ]; }; then
    echo "test files kept in $dir" >&2
  else
    rm -rf "$dir"
  fi
fi
exit $rc
