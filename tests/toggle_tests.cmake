# The toggle matrix (issue 13): every bundled scene × every plugin it loads, switched off and on
# live, against a fresh start with the same setting; keys and debug views must change the image.
sl_add_test(toggle_matrix SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_toggle_matrix.c TIMEOUT 1200 LABELS toggle)
target_compile_definitions(test_toggle_matrix PRIVATE SL_SCENES_DIR="${PROJECT_SOURCE_DIR}/scenes")
