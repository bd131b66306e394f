# ASan + UBSan runs of the test suite (issue 3, hardening; issue 43: the subset).
#
# Included by tests/CMakeLists.txt it registers two tests; run with `cmake -P` (what they do) it
# configures a second build tree with -DSL_SANITIZE=ON (AddressSanitizer +
# UndefinedBehaviorSanitizer, -fno-sanitize-recover), builds what the selected tests need and runs
# them there, two at a time:
#   sanitize      (label hardening)       a representative subset, SL_SANITIZE_TESTS below: the
#                                         core's library (its uniform cache too), plugin loader,
#                                         scene and image readers, parser regressions, the CLI's
#                                         plugin lifecycle, the viewer's keys and hot reload.
#                                         Builds only their targets.
#   sanitize_all  (labels hardening;long) every test, minus those that cannot or need not run
#                                         instrumented: sdk_install (and the extras, not built
#                                         there) load the instrumented harness into
#                                         uninstrumented executables ("ASan runtime does not
#                                         come first"), the window's tests under Xvfb
#                                         (gui_smoke, gui_budget, gui_gltf_animation: covered
#                                         uninstrumented; the GLX driver's leaks come from
#                                         unloaded modules LSan cannot attribute, so no
#                                         suppression names them), fuzz_scene is instrumented
#                                         already.
# Both use one tree (build/sanitize; RESOURCE_LOCK keeps them apart), incremental between runs.
# Leaks inside the GL drivers are suppressed (tests/sanitizers/lsan.supp, with one of
# OpenImageIO's); leaks in shadelab are failures.
# By hand:  ctest --test-dir build -R '^sanitize$' --output-on-failure     (ctest -L long: all)
#     or:   cmake -B build-asan -DSL_SANITIZE=ON -DSL_BUILD_EXTRAS=OFF && cmake --build build-asan -j2 && \
#           ctest --test-dir build-asan -E '^(gui_smoke|gui_budget|gui_gltf_animation|sdk_install|fuzz_scene)$'
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
  # -O1 -g1: -O1 as the sanitizers advise, and line tables, all that the reports' stack traces need;
  # half the compile time of RelWithDebInfo's -O2 -g (this build is most of the test's time)
  execute_process(COMMAND "${CMAKE_COMMAND}" -S "${SRC}" -B "${BIN}" -DSL_SANITIZE=ON -DSL_BUILD_EXTRAS=OFF
                          -DCMAKE_BUILD_TYPE=None "-DCMAKE_C_FLAGS=-O1 -g1" "-DCMAKE_CXX_FLAGS=-O1 -g1"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(rc)
    message("${out}")
    message(FATAL_ERROR "sanitize: configure failed (${rc})")
  endif()
  # TARGETS: what the selected tests need (empty: everything)
  set(targets "")
  if(TARGETS)
    set(targets --target ${TARGETS})
  endif()
  execute_process(COMMAND "${CMAKE_COMMAND}" --build "${BIN}" -j2 ${targets} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(rc)
    message("${out}")
    message(FATAL_ERROR "sanitize: build failed (${rc})")
  endif()
  message(STATUS "sanitize: built; running the tests")
  if(SELECT)
    set(select -R "${SELECT}")
  else()
    set(select -E "^(gui_smoke|gui_budget|gui_gltf_animation|sdk_install|fuzz_scene)$")
  endif()
  # Two at a time, as its build runs two compilers; ctest prints a failing test's output as one
  # block after its status line, so each failure's output stays its own. The
  # sanitizers' options are the tests' environment in that tree (tests/CMakeLists.txt, SL_SANITIZE).
  execute_process(COMMAND "${CMAKE_CTEST_COMMAND}" -N ${select} WORKING_DIRECTORY "${BIN}"
                  OUTPUT_VARIABLE listing RESULT_VARIABLE rc)
  if(rc OR NOT listing MATCHES "Test +#[0-9]+: ")
    message(FATAL_ERROR "sanitize: no tests selected (${rc}):\n${listing}")
  endif()
  execute_process(COMMAND "${CMAKE_CTEST_COMMAND}" --output-on-failure -j2 ${select} WORKING_DIRECTORY "${BIN}"
                  OUTPUT_VARIABLE out ERROR_VARIABLE out RESULT_VARIABLE rc)
  string(REGEX MATCHALL "Test +#[0-9]+: [^\n]*" statuses "${out}")
  foreach(status IN LISTS statuses)
    message("${status}")
  endforeach()
  if(rc)
    message("${out}")
    message(FATAL_ERROR "sanitize: failed under ASan/UBSan (their output is above)")
  endif()
  if(SL_TREE_TMP)
    file(REMOVE_RECURSE "${SL_TREE_TMP}")
  endif()
  message(STATUS "sanitize: every test passed under ASan + UBSan")
  return()
endif()

option(SL_SANITIZE_TEST "Register the ASan+UBSan tests (they build a second tree)" ON)
# The representative subset (test names); each C test's target is built, and the viewer with the
# bundled plugins for the command-line ones. cli_scenes (every bundled scene, 3-4 min under ASan
# on 2 cores) and the plugins' own tests run in sanitize_all.
set(SL_SANITIZE_TESTS core_render core_glsl core_bad_input core_plugins core_zero_cost cli_lazy_programs
    image scene scene_geometry scene_import stability_core gui_keys gui_hot_reload fuzz_regress gltf_hostile
    gltf_models program_uniform)
if(SL_SANITIZE_TEST AND NOT SL_SANITIZE)
  list(JOIN SL_SANITIZE_TESTS "|" sl_select)
  set(sl_targets shadelab bundled_plugins)
  foreach(t ${SL_SANITIZE_TESTS})
    list(APPEND sl_targets "$<TARGET_NAME_IF_EXISTS:test_${t}>")
  endforeach()
  set(sl_sanitize_command ${CMAKE_COMMAND} -DSRC=${PROJECT_SOURCE_DIR} -DBIN=${PROJECT_BINARY_DIR}/sanitize
      -DCMAKE_CTEST_COMMAND=${CMAKE_CTEST_COMMAND})
  add_test(NAME sanitize COMMAND ${sl_sanitize_command} "-DSELECT=^(${sl_select})$" "-DTARGETS=${sl_targets}"
           -P ${CMAKE_CURRENT_LIST_FILE})
  sl_add_long_test(sanitize_all COMMAND ${sl_sanitize_command} -P ${CMAKE_CURRENT_LIST_FILE}
                   LABELS hardening TIMEOUT 5400 RESOURCE_LOCK sanitize_tree)
  set_tests_properties(sanitize PROPERTIES ENVIRONMENT "${SL_TEST_ENV}" TIMEOUT 3600 LABELS hardening
                       RESOURCE_LOCK sanitize_tree)
endif()
