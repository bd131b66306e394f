# Fewer fixed full-screen passes (issue 18 item 3): the display encoding written on the fly by the
# last passes (display_on_write) against the display pass and a CPU sRGB encoding.
sl_add_test(display_on_write SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_display_on_write.c TIMEOUT ${SL_HANG_GUARD})
target_compile_definitions(test_display_on_write PRIVATE SL_SCENES_DIR="${PROJECT_SOURCE_DIR}/scenes")
# Fused full-screen passes (ext/post.h): tonemap inside TAA's draw against each pass on its own.
sl_add_test(post_fusion SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_post_fusion.c TIMEOUT ${SL_HANG_GUARD})
add_dependencies(test_post_fusion plugin_aa plugin_tonemap plugin_ggx)
# The upscaler (ABI 1.18, SL_SIZE_OUTPUT): "color" at the render size before it, at the output size
# from it on; the core's bilinear scale-up while it does not run.
sl_add_test_plugin(tp-upscale DIR ${PROJECT_BINARY_DIR}/tests/plugins PREFIX tp_
                   SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/plugins/tp_upscale.c GLSL plugins/tp_upscale.frag)
sl_add_test(upscaler SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_upscaler.c TIMEOUT ${SL_HANG_GUARD})
target_compile_definitions(test_upscaler PRIVATE SL_TEST_PLUGIN_DIR="${PROJECT_BINARY_DIR}/tests/plugins")
add_dependencies(test_upscaler tp_tp-upscale)
