# glTF 2.0 import (issue 15): fixtures written by the test itself (tests/test_gltf.c), and the
# glTF2 models Debian ships in assimp-testmodels against a committed table of outcomes
# (tests/test_gltf_models.c, tests/data/gltf_models.tsv).
sl_add_test(gltf SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_gltf.c LABELS scene gltf TIMEOUT ${SL_HANG_GUARD})
sl_add_test(gltf_models SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_gltf_models.c LABELS scene gltf TIMEOUT ${SL_HANG_GUARD})
# glTF alphaMode BLEND (order, background, envmap, ssaa, TAA, shadows) and animated nodes' motion
# vectors (tests/test_gltf_blend.c); tp-motion shows the core's "motion" as colour.
sl_add_test_plugin(tp-motion DIR ${PROJECT_BINARY_DIR}/tests/plugins PREFIX tp_
                   SOURCES ${CMAKE_CURRENT_LIST_DIR}/plugins/tp_motion.c GLSL plugins/tp_motion.frag)
sl_add_test(gltf_blend SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_gltf_blend.c LABELS scene gltf TIMEOUT ${SL_HANG_GUARD})
target_compile_definitions(test_gltf_blend PRIVATE TP_MOTION_PATH="${PROJECT_BINARY_DIR}/tests/plugins/tp-motion/tp-motion.so")
add_dependencies(test_gltf_blend tp_tp-motion plugin_aa plugin_envmap plugin_ggx plugin_spotlight-shadow)
# Hostile and unusual glTF written by the test (tests/test_gltf_hostile.c, tests/gltf_writer.h):
# every family refused naming the file, JSON pointer and cause, or opened naming what was dropped.
sl_add_test(gltf_hostile SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_gltf_hostile.c LABELS scene gltf hostile TIMEOUT ${SL_HANG_GUARD})
# Vertex colours (COLOR_0) against baseColorFactor × the interpolated colours, float VEC3 and
# normalized u8 VEC4 under alphaMode BLEND (tests/test_gltf_color.c).
sl_add_test(gltf_color SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_gltf_color.c LABELS scene gltf TIMEOUT ${SL_HANG_GUARD})
# A model needs no JSON: --variant, --animation, --ground, --shadows, --env (tests/test_gltf_options.c).
sl_add_test(gltf_options SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_gltf_options.c LABELS scene gltf TIMEOUT ${SL_HANG_GUARD})
add_dependencies(test_gltf_options plugin_envmap plugin_ggx plugin_spotlight-shadow plugin_tonemap plugin_aa)
# Compressed content on files the test writes: EXT_texture_webp, EXT_meshopt_compression,
# KHR_draco_mesh_compression (tests/test_gltf_compressed.c).
sl_add_test(gltf_compressed SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_gltf_compressed.c ${CMAKE_CURRENT_LIST_DIR}/draco_encode.cpp
            LABELS scene gltf TIMEOUT ${SL_HANG_GUARD})
target_link_libraries(test_gltf_compressed PRIVATE draco::draco meshoptimizer::meshoptimizer) # the test's own encoders
add_dependencies(test_gltf_compressed plugin_envmap plugin_ggx plugin_tonemap plugin_aa shadelab_draco)
# Skins and morph targets on the GPU against the specification's formulas on the CPU, their motion
# vectors and hostile skin/morph files (tests/test_gltf_skin.c).
sl_add_test(gltf_skin SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_gltf_skin.c LABELS scene gltf hostile TIMEOUT ${SL_HANG_GUARD})
target_compile_definitions(test_gltf_skin PRIVATE TP_MOTION_PATH="${PROJECT_BINARY_DIR}/tests/plugins/tp-motion/tp-motion.so")
add_dependencies(test_gltf_skin tp_tp-motion plugin_spotlight-shadow)
