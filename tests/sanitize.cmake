# ASan + UBSan run of the test suite (issue 3, hardening).
#
# Included by tests/CMakeLists.txt it registers the test `sanitize`; run with `cmake -P` (what
# the test does) it configures a second build tree with -DSL_SANITIZE=ON (AddressSanitizer +
# UndefinedBehaviorSanitizer, -fno-sanitize-recover), builds it and runs the core's tests there
# (SL_SANITIZE_CORE_TESTS below). With -DSL_SANITIZE_ALL_TESTS=ON it runs every test instead
# (the bundled plugins' too), minus those that cannot or need not run instrumented: sdk_install
# and extras load the instrumented harness into uninstrumented executables (the extras are built
# out of tree against the installed SDK; "ASan runtime does not come first"), gui_smoke runs under Xvfb
# (covered uninstrumented; the GLX driver's leaks come from unloaded modules LSan cannot
# attribute), fuzz_scene is instrumented already. Leaks inside the GL drivers are suppressed
# (tests/sanitizers/lsan.supp, with one of OpenImageIO's); leaks in shadelab are failures.
# Cost on 2 idle cores: about 2 minutes to build the tree, about 1 minute for the core tests
# (every test: about 7 more); later runs are incremental.
# By hand:  ctest --test-dir build -R '^sanitize$' --output-on-failure
#     or:   cmake -B build-asan -DSL_SANITIZE=ON && cmake --build build-asan -j2 && \
#           ctest --test-dir build-asan -E '^(gui_smoke|sdk_install|extras|fuzz_scene)$'   # everything
if(CMAKE_SCRIPT_MODE_FILE)
  foreach(v SRC BIN)
    if(NOT DEFINED ${v})
      message(FATAL_ERROR "sanitize.cmake: -D${v}= is required")
    endif()
  endforeach()
  # BIN stays between runs (incremental); in a read-only or copied build tree, a temporary tree
  include("${CMAKE_CURRENT_LIST_DIR}/tree_or_tmp.cmake")
  sl_tree_or_tmp(BIN sanitize)
  # configure and build quietly (their output, thousands of lines, would bury a failing test's
  # in a log that readers see only the ends of): shown only when they fail
  message(STATUS "sanitize: configuring and building ${BIN} (ASan + UBSan)")
  execute_process(COMMAND "${CMAKE_COMMAND}" -S "${SRC}" -B "${BIN}" -DSL_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(rc)
    message("${out}")
    message(FATAL_ERROR "sanitize: configure failed (${rc})")
  endif()
  execute_process(COMMAND "${CMAKE_COMMAND}" --build "${BIN}" -j2 RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(rc)
    message("${out}")
    message(FATAL_ERROR "sanitize: build failed (${rc})")
  endif()
  message(STATUS "sanitize: built; running the tests")
  if(ALL)
    set(select -E "^(gui_smoke|sdk_install|extras|fuzz_scene)$")
  else()
    set(select -R "${CORE_TESTS}")
  endif()
  # One test at a time, so that each failure's output is its own. The sanitizers' options are the
  # tests' environment in that tree (tests/CMakeLists.txt, SL_SANITIZE).
  execute_process(COMMAND "${CMAKE_CTEST_COMMAND}" -N ${select} WORKING_DIRECTORY "${BIN}"
                  OUTPUT_VARIABLE listing RESULT_VARIABLE rc)
  string(REGEX MATCHALL "Test +#[0-9]+: [A-Za-z0-9_.-]+" entries "${listing}")
  if(rc OR NOT entries)
    message(FATAL_ERROR "sanitize: no tests selected (${rc}):\n${listing}")
  endif()
  set(failed "")
  foreach(e IN LISTS entries)
    string(REGEX REPLACE "^Test +#[0-9]+: " "" name "${e}")
    execute_process(COMMAND "${CMAKE_CTEST_COMMAND}" --output-on-failure -R "^${name}$" WORKING_DIRECTORY "${BIN}"
                    OUTPUT_VARIABLE out ERROR_VARIABLE out RESULT_VARIABLE rc)
    string(REGEX MATCH "Test +#[0-9]+: [^\n]*" status "${out}")
    message("${status}")
    if(rc)
      message("${out}")
      list(APPEND failed ${name})
    endif()
  endforeach()
  if(failed)
    message(FATAL_ERROR "sanitize: failed under ASan/UBSan: ${failed} (their output is above)")
  endif()
  if(SL_TREE_TMP)
    file(REMOVE_RECURSE "${SL_TREE_TMP}")
  endif()
  message(STATUS "sanitize: every test passed under ASan + UBSan")
  return()
endif()

option(SL_SANITIZE_TEST "Register the ASan+UBSan test (builds a second tree)" ON)
option(SL_SANITIZE_ALL_TESTS "The ASan+UBSan test runs every test, plugins' too (slower)" OFF)
# The core's tests: the core library, scenes, images, the CLI (with lazy programs: a plugin
# disabled by a failing compile is still destroyed), the viewer's keys and hot reload, the
# scene-parser regression inputs.
set(SL_SANITIZE_CORE_TESTS "^(core_.*|cli_scenes|cli_lazy_programs|image|scene.*|stability_core|gui_keys|gui_hot_reload|fuzz_regress|gltf_hostile|gltf_models)$")
if(SL_SANITIZE_TEST AND NOT SL_SANITIZE)
  add_test(NAME sanitize COMMAND ${CMAKE_COMMAND} -DSRC=${PROJECT_SOURCE_DIR} -DBIN=${PROJECT_BINARY_DIR}/sanitize
                                 -DCMAKE_CTEST_COMMAND=${CMAKE_CTEST_COMMAND} -DALL=${SL_SANITIZE_ALL_TESTS}
                                 "-DCORE_TESTS=${SL_SANITIZE_CORE_TESTS}" -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(sanitize PROPERTIES ENVIRONMENT "${SL_TEST_ENV}" TIMEOUT 1500 LABELS hardening)
endif()
