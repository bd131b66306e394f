# The interactive viewer (issue 3): key bindings, hot reload, and the GUI smoke test under Xvfb.

# The SDK example, built in tree as well (the out-of-tree build is tests/sdk_install.sh): the
# hot-reload and GUI tests load a copy of it by path.
set(SL_TEST_EXAMPLE_DIR ${PROJECT_BINARY_DIR}/tests/example)
add_library(sl_test_example MODULE ${PROJECT_SOURCE_DIR}/sdk/example/example.c)
set_target_properties(sl_test_example PROPERTIES PREFIX "" OUTPUT_NAME example
  LIBRARY_OUTPUT_DIRECTORY ${SL_TEST_EXAMPLE_DIR} C_VISIBILITY_PRESET hidden)
target_link_libraries(sl_test_example PRIVATE shadelab_sdk)
add_custom_command(TARGET sl_test_example POST_BUILD
  COMMAND ${CMAKE_COMMAND} -E copy_if_different ${PROJECT_SOURCE_DIR}/sdk/example/tint.glsl
          ${PROJECT_SOURCE_DIR}/sdk/example/vignette.frag ${SL_TEST_EXAMPLE_DIR})

# Two plugins that want the same keys (and some of the viewer's).
foreach(k a b)
  add_library(sl_test_keys_${k} MODULE ${CMAKE_CURRENT_LIST_DIR}/gui_keys_plugin.c)
  set_target_properties(sl_test_keys_${k} PROPERTIES PREFIX "" OUTPUT_NAME keys-${k}
    LIBRARY_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests/keys-${k} C_VISIBILITY_PRESET hidden)
  target_compile_definitions(sl_test_keys_${k} PRIVATE KEYS_ID="keys-${k}")
  target_link_libraries(sl_test_keys_${k} PRIVATE shadelab_sdk)
endforeach()

sl_add_test(gui_keys SOURCES ${CMAKE_CURRENT_LIST_DIR}/gui_keys.c LABELS gui)
target_link_libraries(test_gui_keys PRIVATE shadelab_viewer)
target_compile_definitions(test_gui_keys PRIVATE
  SL_KEYS_A="$<TARGET_FILE:sl_test_keys_a>" SL_KEYS_B="$<TARGET_FILE:sl_test_keys_b>")
add_dependencies(test_gui_keys sl_test_keys_a sl_test_keys_b)

sl_add_test(gui_hot_reload SOURCES ${CMAKE_CURRENT_LIST_DIR}/gui_hot_reload.c LABELS gui)
target_compile_definitions(test_gui_hot_reload PRIVATE SL_EXAMPLE_DIR="${SL_TEST_EXAMPLE_DIR}")
add_dependencies(test_gui_hot_reload sl_test_example)

# The windowed viewer under Xvfb (GLFW + Mesa llvmpipe GLX): exit code 77 = skipped (no
# xvfb-run), reported as "Not Run" with the reason.
add_test(NAME gui_smoke
         COMMAND ${CMAKE_CURRENT_LIST_DIR}/gui_smoke.sh $<TARGET_FILE:shadelab> $<TARGET_FILE:sl-imgdiff>
                 ${SL_TEST_EXAMPLE_DIR} $<TARGET_FILE:sl_test_keys_a> $<TARGET_FILE:sl_test_keys_b>
                 $<TARGET_FILE:sl-xkey>)
set_tests_properties(gui_smoke PROPERTIES ENVIRONMENT "${SL_TEST_ENV}" TIMEOUT 300 LABELS gui SKIP_RETURN_CODE 77)

# Real key presses for the smoke test (XTEST, loaded at run time).
add_executable(sl-xkey ${CMAKE_CURRENT_LIST_DIR}/gui_xkey.c)
target_link_libraries(sl-xkey PRIVATE ${CMAKE_DL_LIBS})
