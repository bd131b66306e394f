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
  # A displaced material whose texture reads the second UV set (Debian's BoxTexcoords: its
  # metallic-roughness map on TEXCOORD_1): the tessellation stages carry the set as forward.vert
  # does, so the program links and the frame renders (exit 0).
  add_test(NAME extras_displacement_uv1
           COMMAND ${CMAKE_CURRENT_LIST_DIR}/run_in_tmpdir.sh extras_displacement_uv1 $<TARGET_FILE:shadelab>
                   --headless --size 64x64 --plugin displacement --set material.boxTexcoords/Material.displace=0.05
                   --output @TMP@/uv1.png /usr/share/assimp/models/glTF2/BoxTexcoords-glTF/boxTexcoords.gltf)
  set_tests_properties(extras_displacement_uv1 PROPERTIES ENVIRONMENT "${SL_TEST_ENV}" TIMEOUT ${SL_HANG_GUARD}
                       LABELS "extras;gltf")
  add_test(NAME extras_sdk_only COMMAND ${CMAKE_CURRENT_LIST_DIR}/extras.sh ${PROJECT_SOURCE_DIR}/extras)
  set_tests_properties(extras_sdk_only PROPERTIES LABELS "extras;sdk;architecture" TIMEOUT ${SL_HANG_GUARD})
endif()
