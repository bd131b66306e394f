# The interactive viewer (issue 3): key bindings, hot reload, and the GUI smoke test under Xvfb.

# The SDK example, built in tree as well (the out-of-tree build is tests/sdk_install.sh): the
# hot-reload and GUI tests load a copy of it by path.
set(SL_TEST_EXAMPLE_DIR ${PROJECT_BINARY_DIR}/tests/example)
sl_add_test_plugin(example DIR ${PROJECT_BINARY_DIR}/tests PREFIX sl_test_ SOURCES ${PROJECT_SOURCE_DIR}/sdk/example/example.c
                   GLSL ${PROJECT_SOURCE_DIR}/sdk/example/tint.glsl ${PROJECT_SOURCE_DIR}/sdk/example/vignette.frag)

# Two plugins that want the same keys (and some of the viewer's).
foreach(k a b)
  sl_add_test_plugin(keys-${k} DIR ${PROJECT_BINARY_DIR}/tests PREFIX sl_test_ SOURCES ${CMAKE_CURRENT_LIST_DIR}/gui_keys_plugin.c)
  target_compile_definitions(sl_test_keys-${k} PRIVATE KEYS_ID="keys-${k}")
endforeach()

sl_add_test(gui_keys SOURCES ${CMAKE_CURRENT_LIST_DIR}/gui_keys.c LABELS gui)
target_link_libraries(test_gui_keys PRIVATE shadelab_viewer)
target_compile_definitions(test_gui_keys PRIVATE
  SL_KEYS_A="$<TARGET_FILE:sl_test_keys-a>" SL_KEYS_B="$<TARGET_FILE:sl_test_keys-b>")
add_dependencies(test_gui_keys sl_test_keys-a sl_test_keys-b)

sl_add_test(gui_hot_reload SOURCES ${CMAKE_CURRENT_LIST_DIR}/gui_hot_reload.c LABELS gui)
target_compile_definitions(test_gui_hot_reload PRIVATE SL_EXAMPLE_DIR="${SL_TEST_EXAMPLE_DIR}")
add_dependencies(test_gui_hot_reload sl_test_example)

# The windowed viewer under Xvfb (GLFW + Mesa llvmpipe GLX): exit code 77 = skipped (no
# xvfb-run), reported as "Not Run" with the reason.
add_test(NAME gui_smoke
         COMMAND ${CMAKE_CURRENT_LIST_DIR}/gui_smoke.sh $<TARGET_FILE:shadelab> $<TARGET_FILE:sl-imgdiff>
                 ${SL_TEST_EXAMPLE_DIR} $<TARGET_FILE:sl_test_keys-a> $<TARGET_FILE:sl_test_keys-b>
                 $<TARGET_FILE:sl-xkey> ${PROJECT_SOURCE_DIR}/scenes/basic.json)
set_tests_properties(gui_smoke PROPERTIES ENVIRONMENT "${SL_TEST_ENV}" TIMEOUT ${SL_HANG_GUARD} LABELS gui SKIP_RETURN_CODE 77)

# Real key presses for the smoke test (XTEST, loaded at run time).
add_executable(sl-xkey ${CMAKE_CURRENT_LIST_DIR}/gui_xkey.c)
target_link_libraries(sl-xkey PRIVATE ${CMAKE_DL_LIBS})

# The window's frame-time budget: chooses while moving, converges to the headless still when still.
add_test(NAME gui_budget COMMAND ${CMAKE_CURRENT_LIST_DIR}/gui_budget.sh $<TARGET_FILE:shadelab> $<TARGET_FILE:sl-imgdiff>)
set_tests_properties(gui_budget PROPERTIES LABELS "gui" TIMEOUT ${SL_HANG_GUARD} SKIP_RETURN_CODE 77 ENVIRONMENT "${SL_TEST_ENV_OPTIMISED}")

# The window at rest: once the still is complete it waits for events; an animated scene keeps drawing.
add_test(NAME gui_rest COMMAND ${CMAKE_CURRENT_LIST_DIR}/gui_rest.sh $<TARGET_FILE:shadelab>
                               ${PROJECT_SOURCE_DIR}/scenes/shadow_many_spots.json)
set_tests_properties(gui_rest PROPERTIES LABELS "gui" TIMEOUT ${SL_HANG_GUARD} SKIP_RETURN_CODE 77 ENVIRONMENT "${SL_TEST_ENV}")

# A glTF skin and morph-target animation plays in the window as under --time (Xvfb; 77 = skipped).
add_test(NAME gui_gltf_animation COMMAND ${CMAKE_CURRENT_LIST_DIR}/gui_gltf_animation.sh $<TARGET_FILE:shadelab> $<TARGET_FILE:sl-imgdiff>)
set_tests_properties(gui_gltf_animation PROPERTIES LABELS "gui;gltf" TIMEOUT ${SL_HANG_GUARD} SKIP_RETURN_CODE 77 ENVIRONMENT "${SL_TEST_ENV}")
