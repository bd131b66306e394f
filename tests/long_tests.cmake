# Long tests (label `long`): exhaustive sweeps that a plain `ctest` leaves out, so that the
# README's test command fits in its time on 2 cores; CI runs them separately with `ctest -L long`.
#
# CTest has no label that is off by default, so a long test exists only when the ctest command
# line asks for it: a label regex (-L, --label-regex) that matches "long", or a test regex (-R,
# --tests-regex) that matches its name. Or always, with SL_LONG_TESTS=1 in the environment (where
# ctest's command line cannot be read: no /proc). Two modes:
#   - included at configure time (tests/CMakeLists.txt includes every tests/*.cmake): defines
#     sl_add_long_test() and has ctest include this file;
#   - included by ctest, from build/tests/long_tests.ctest (generated at configure time, included
#     by build/tests/CTestTestfile.cmake): reads ctest's command line; the lines after the include
#     then register the long tests that were asked for.
#
#   sl_add_long_test(NAME COMMAND cmd args... [LABELS l...] [TIMEOUT s] [RESOURCE_LOCK r])
#     a test with the label `long` (and LABELS), the suite's environment, working directory
#     build/; generator expressions work in COMMAND.
if(CMAKE_PARENT_LIST_FILE MATCHES "long_tests\\.ctest$")
  set(sl_labels "")
  set(sl_names "")
  if(EXISTS /proc/self/cmdline)
    file(STRINGS /proc/self/cmdline sl_args LENGTH_MINIMUM 1)
    set(sl_next "")
    foreach(a IN LISTS sl_args)
      if(sl_next)
        list(APPEND ${sl_next} "${a}")
        set(sl_next "")
      elseif(a STREQUAL "-L" OR a STREQUAL "--label-regex")
        set(sl_next sl_labels)
      elseif(a STREQUAL "-R" OR a STREQUAL "--tests-regex")
        set(sl_next sl_names)
      endif()
    endforeach()
  endif()
  set(sl_all "$ENV{SL_LONG_TESTS}")
  foreach(l IN LISTS sl_labels)
    if("long" MATCHES "${l}")
      set(sl_all 1)
    endif()
  endforeach()
  # long_tests.ctest: per test, sl_long_test(NAME) and its add_test and set_tests_properties
  macro(sl_long_test name)
    set(sl_wanted "${sl_all}")
    foreach(r IN LISTS sl_names)
      if("${name}" MATCHES "${r}")
        set(sl_wanted 1)
      endif()
    endforeach()
  endmacro()
  macro(sl_long_add_test)
    if(sl_wanted)
      add_test(${ARGN})
    endif()
  endmacro()
  macro(sl_long_set_tests_properties)
    if(sl_wanted)
      set_tests_properties(${ARGN})
    endif()
  endmacro()
  return()
endif()
if(CMAKE_SCRIPT_MODE_FILE)
  return()
endif()

set_property(GLOBAL PROPERTY SL_LONG_TESTS_TEXT "")
function(sl_add_long_test name)
  cmake_parse_arguments(T "" "TIMEOUT;RESOURCE_LOCK" "COMMAND;LABELS" ${ARGN})
  set(command "")
  foreach(a IN LISTS T_COMMAND)
    string(APPEND command " [==[${a}]==]")
  endforeach()
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 3600)
  endif()
  set(props "LABELS [==[long;${T_LABELS}]==] TIMEOUT ${T_TIMEOUT} ENVIRONMENT [==[${SL_TEST_ENV}]==]")
  string(APPEND props " WORKING_DIRECTORY [==[${PROJECT_BINARY_DIR}]==]")
  if(T_RESOURCE_LOCK)
    string(APPEND props " RESOURCE_LOCK [==[${T_RESOURCE_LOCK}]==]")
  endif()
  set_property(GLOBAL APPEND_STRING PROPERTY SL_LONG_TESTS_TEXT
    "sl_long_test([==[${name}]==])\nsl_long_add_test([==[${name}]==]${command})\nsl_long_set_tests_properties([==[${name}]==] PROPERTIES ${props})\n")
endfunction()

# Written once every directory (the plugins' too) has added its long tests.
function(sl_write_long_tests)
  get_property(text GLOBAL PROPERTY SL_LONG_TESTS_TEXT)
  file(GENERATE OUTPUT "${PROJECT_BINARY_DIR}/tests/long_tests.ctest"
       CONTENT "include([==[${CMAKE_CURRENT_FUNCTION_LIST_FILE}]==])\n${text}")
endfunction()
cmake_language(DEFER DIRECTORY "${PROJECT_SOURCE_DIR}" CALL sl_write_long_tests)
set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${PROJECT_BINARY_DIR}/tests/long_tests.ctest")
