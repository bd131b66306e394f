# The toggle matrix (issue 13): every scene × the plugins it loads, switched off and on live,
# against a fresh start with the same setting; keys and debug views must change the image.
# `toggle_matrix`: a pairwise design over each scene's plugins; `toggle_matrix_exhaustive`
# (label long): every plugin off alone and every two together, every feature on every scene.
# The bundled scenes, and the extras' scenes where the build makes their plugins.
set(SL_TOGGLE_SCENE_DIRS ${PROJECT_SOURCE_DIR}/scenes)
if(SL_BUILD_EXTRAS)
  file(GLOB SL_EXTRA_SCENE_DIRS LIST_DIRECTORIES true ${PROJECT_SOURCE_DIR}/extras/*/scenes)
  list(APPEND SL_TOGGLE_SCENE_DIRS ${SL_EXTRA_SCENE_DIRS})
  # the toon and ssao examples' scenes name area-light, an extra
  list(APPEND SL_TOGGLE_SCENE_DIRS ${PROJECT_SOURCE_DIR}/sdk/example/toon/scenes ${PROJECT_SOURCE_DIR}/sdk/example/ssao/scenes)
endif()
sl_add_test(toggle_matrix SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_toggle_matrix.c ARGS ${SL_TOGGLE_SCENE_DIRS}
            TIMEOUT 3600 LABELS toggle)
# Its cells render 48×32 images with hundreds of distinct programs: unoptimised shaders
# (SL_TEST_ENV, tests/CMakeLists.txt) cut its CPU time by a fifth (163 s -> 127 s, cold cache).
sl_add_long_test(toggle_matrix_exhaustive COMMAND $<TARGET_FILE:test_toggle_matrix> --exhaustive ${SL_TOGGLE_SCENE_DIRS}
                 LABELS toggle)
