# Fuzzing of shadelab's own scene parser (issue 3, hardening).
#
#  fuzz_regress  every input in tests/data/fuzz/ (crashes the fuzzer found, and hand-made edge
#                cases) loads without crashing: a clean error or a scene. Runs in the normal
#                build and, instrumented, in the `sanitize` test's ASan/UBSan build.
#  fuzz_scene    builds fuzz/ with clang + libFuzzer (+ ASan/UBSan) into build/fuzz and fuzzes
#                sl_scene_load_text for 10 s from the seed corpus scenes/*.json,
#                tests/data/scenes/*.json and tests/data/fuzz/*. Skipped (with the reason) when
#                clang or libFuzzer (libclang-rt-14-dev) is missing. A crash fails the test and
#                leaves the input in build/fuzz/artifacts/: copy it into tests/data/fuzz/.
#  fuzz_gltf     the same for the glTF reader (fuzz/gltf_fuzzer.c, sl_scene_import_gltf) for 10 s
#                from tests/data/fuzz_gltf/ (the files tests/test_gltf_hostile.c writes, whose
#                gltf_hostile test loads every file there: a found crash goes there).
# Longer runs: fuzz/README.md.
if(CMAKE_SCRIPT_MODE_FILE)
  find_program(CLANG clang)
  if(NOT CLANG)
    message("SKIP: clang not found (apt install clang libclang-rt-14-dev; tools/install-deps.sh)")
    return()
  endif()
  execute_process(COMMAND ${CLANG} -print-file-name=libclang_rt.fuzzer-x86_64.a OUTPUT_VARIABLE fz OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT EXISTS "${fz}")
    message("SKIP: libFuzzer runtime not found (apt install libclang-rt-14-dev; tools/install-deps.sh)")
    return()
  endif()
  # BIN stays between runs (the corpus grows); in a read-only or copied build tree, a temporary one
  include(${CMAKE_CURRENT_LIST_DIR}/tree_or_tmp.cmake)
  sl_tree_or_tmp(BIN fuzz)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env CC=${CLANG} ${CMAKE_COMMAND} -S ${SRC}/fuzz -B ${BIN}
                          -DCMAKE_BUILD_TYPE=RelWithDebInfo RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "fuzz: configure failed")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${BIN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "fuzz: build failed")
  endif()
  # the corpus grows in the build tree between runs; the seeds come from the source tree
  if(FUZZER STREQUAL "gltf_fuzzer")
    file(MAKE_DIRECTORY ${BIN}/gltf_corpus ${BIN}/artifacts)
    execute_process(COMMAND ${BIN}/gltf_fuzzer -dict=${SRC}/fuzz/gltf.dict -max_total_time=${SECONDS} -timeout=60
                            -rss_limit_mb=4096 -max_len=65536 -print_final_stats=1 -artifact_prefix=${BIN}/artifacts/
                            ${BIN}/gltf_corpus ${SRC}/tests/data/fuzz_gltf
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
    string(REGEX MATCH "stat::number_of_executed_units: *[0-9]+" runs "${out}")
    if(NOT rc EQUAL 0)
      string(REGEX MATCHALL "Test unit written to [^\n]*" units "${out}")
      message("${out}")
      message(FATAL_ERROR "fuzz: the glTF reader failed on a generated input (${units}). Copy it into "
              "tests/data/fuzz_gltf/ so that gltf_hostile keeps checking it, then fix the reader.")
    endif()
    if(SL_TREE_TMP)
      file(REMOVE_RECURSE "${SL_TREE_TMP}")
    endif()
    message(STATUS "fuzz: ${SECONDS} s of sl_scene_import_gltf without a crash (${runs})")
    return()
  endif()
  file(MAKE_DIRECTORY ${BIN}/corpus ${BIN}/artifacts)
  file(GLOB seeds ${SRC}/scenes/*.json ${SRC}/tests/data/scenes/*.json)
  file(COPY ${seeds} DESTINATION ${BIN}/seeds)
  file(GLOB regress ${SRC}/tests/data/fuzz/*)
  list(FILTER regress EXCLUDE REGEX "README|max_tessellation") # the latter: seconds per run
  if(regress)
    file(COPY ${regress} DESTINATION ${BIN}/seeds)
  endif()
  if(NOT SECONDS)
    set(SECONDS 20)
  endif()
  execute_process(COMMAND ${BIN}/scene_fuzzer -dict=${SRC}/fuzz/scene.dict -max_total_time=${SECONDS} -timeout=60
                          -rss_limit_mb=4096 -max_len=16384 -print_final_stats=1 -artifact_prefix=${BIN}/artifacts/
                          ${BIN}/corpus ${BIN}/seeds
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  string(REGEX MATCH "stat::number_of_executed_units: *[0-9]+" runs "${out}")
  if(NOT rc EQUAL 0)
    string(REGEX MATCHALL "Test unit written to [^\n]*" units "${out}")
    message("${out}")
    message(FATAL_ERROR "fuzz: sl_scene_load_text failed on a generated input (${units}). "
            "Copy it into tests/data/fuzz/ so that fuzz_regress keeps checking it, then fix the parser.")
  endif()
  if(SL_TREE_TMP)
    file(REMOVE_RECURSE "${SL_TREE_TMP}")
  endif()
  message(STATUS "fuzz: ${SECONDS} s of sl_scene_load_text without a crash (${runs})")
  return()
endif()

sl_add_test(fuzz_regress SOURCES ${CMAKE_CURRENT_LIST_DIR}/fuzz_regress.c LABELS hardening)
add_test(NAME fuzz_scene COMMAND ${CMAKE_COMMAND} -DSRC=${PROJECT_SOURCE_DIR} -DBIN=${PROJECT_BINARY_DIR}/fuzz
                                 -DSECONDS=10 -P ${CMAKE_CURRENT_LIST_FILE})
set_tests_properties(fuzz_scene PROPERTIES TIMEOUT ${SL_HANG_GUARD} LABELS hardening SKIP_REGULAR_EXPRESSION "SKIP: ")
add_test(NAME fuzz_gltf COMMAND ${CMAKE_COMMAND} -DSRC=${PROJECT_SOURCE_DIR} -DBIN=${PROJECT_BINARY_DIR}/fuzz
                                -DSECONDS=10 -DFUZZER=gltf_fuzzer -P ${CMAKE_CURRENT_LIST_FILE})
set_tests_properties(fuzz_gltf PROPERTIES TIMEOUT ${SL_HANG_GUARD} LABELS "hardening;gltf" SKIP_REGULAR_EXPRESSION "SKIP: "
                     RESOURCE_LOCK fuzz_build)
set_tests_properties(fuzz_scene PROPERTIES RESOURCE_LOCK fuzz_build)
