# sl_tree_or_tmp(VAR NAME), for the tests that keep a build tree of their own between runs
# (sanitize, fuzz_scene; both run in cmake -P mode). VAR names that tree's directory inside the
# build tree; it stays there when it can, so that later runs are incremental. A build tree that
# is read-only, or a copy (the tree's CMakeCache.txt names another directory), cannot hold it:
# VAR then becomes a fresh $TMPDIR/shadelab-NAME-XXXXXXXX (TMPDIR unset: /tmp), also returned
# in SL_TREE_TMP (empty otherwise) for the caller to remove when it is done.
# This file only defines the function (tests/CMakeLists.txt includes every tests/*.cmake).
function(sl_tree_or_tmp var name)
  set(dir "${${var}}")
  execute_process(COMMAND "${CMAKE_COMMAND}" -E make_directory "${dir}" RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
  if(rc EQUAL 0)
    execute_process(COMMAND "${CMAKE_COMMAND}" -E touch "${dir}/.sl-writable" RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
    file(REMOVE "${dir}/.sl-writable")
  endif()
  if(rc EQUAL 0 AND EXISTS "${dir}/CMakeCache.txt")
    file(STRINGS "${dir}/CMakeCache.txt" owner REGEX "^CMAKE_CACHEFILE_DIR:INTERNAL=")
    if(NOT owner STREQUAL "CMAKE_CACHEFILE_DIR:INTERNAL=${dir}")
      set(rc 1)
    endif()
  endif()
  set(SL_TREE_TMP "" PARENT_SCOPE)
  if(rc EQUAL 0)
    return()
  endif()
  set(tmp "$ENV{TMPDIR}")
  if(NOT tmp)
    set(tmp /tmp)
  endif()
  string(RANDOM LENGTH 8 r)
  while(EXISTS "${tmp}/shadelab-${name}-${r}")
    string(RANDOM LENGTH 8 r)
  endwhile()
  set(dir "${tmp}/shadelab-${name}-${r}")
  file(MAKE_DIRECTORY "${dir}")
  message(STATUS "${name}: ${${var}} cannot be used (read-only, or a copy of another build tree); using ${dir}")
  set(${var} "${dir}" PARENT_SCOPE)
  set(SL_TREE_TMP "${dir}" PARENT_SCOPE)
endfunction()
