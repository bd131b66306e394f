#!/bin/sh
# Regenerates sdk/include/shadelab/gl_aliases.h from the SL_GL_FUNCTIONS list in gl.h.
# Run after adding an entry point to the list.
cd "$(dirname "$0")/../sdk/include/shadelab" || exit 1
{
  echo "/* Generated from SL_GL_FUNCTIONS in gl.h by tools/gen-gl-aliases.sh: plain GL names → this module's pointers. */"
  grep -o 'X(PFN[A-Z0-9]*PROC, gl[A-Za-z0-9]*)' gl.h | sed -E 's/X\(PFN[A-Z0-9]*PROC, (gl[A-Za-z0-9]*)\)/#define \1 sl_\1/'
} > gl_aliases.h
