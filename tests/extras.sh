#!/usr/bin/env bash
# The extras include nothing of the core's or the bundled plugins' sources: everything a module
# includes from shadelab comes from the installed SDK (<shadelab/...>). The build compiles them
# against an installed prefix, where a quoted include of the core's tree would not resolve; this
# also refuses a path into the source tree written so that it would.
#   usage: extras.sh EXTRAS_DIR
set -u
if grep -rnE '#include +"[^"]*(core|plugins)/' "$1" --include='*.c' --include='*.h' --include='*.cpp'; then
  echo "FAIL: an extra includes a core or bundled plugin source file (above)"
  exit 1
fi
echo "PASS: the extras include only the installed SDK"
