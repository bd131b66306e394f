# Extra-credit modules (extras/), built by the build itself against the SDK installed into
# build/sdk-prefix (CMakeLists.txt, "extras"): each module's own tests, run by ctest in its build
# folder, and a check that no module includes a core or bundled-plugin source file.
if(SL_BUILD_EXTRAS)
  file(GLOB SL_EXTRA_MODULES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/extras/*/CMakeLists.txt)
  foreach(f ${SL_EXTRA_MODULES})
    get_filename_component(dir ${f} DIRECTORY)
    get_filename_component(module ${dir} NAME)
    add_test(NAME extras_${module}
             COMMAND ${CMAKE_CTEST_COMMAND} --test-dir ${PROJECT_BINARY_DIR}/extras/${module} --output-on-failure
                     --no-tests=error)
    set_tests_properties(extras_${module} PROPERTIES ENVIRONMENT "${SL_TEST_ENV}" TIMEOUT 3600 LABELS "extras;sdk")
  endforeach()
  add_test(NAME extras_sdk_only COMMAND ${CMAKE_CURRENT_LIST_DIR}/extras.sh ${PROJECT_SOURCE_DIR}/extras)
  set_tests_properties(extras_sdk_only PROPERTIES LABELS "extras;sdk;architecture" TIMEOUT ${SL_HANG_GUARD})
endif()
