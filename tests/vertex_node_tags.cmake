# ABI 1.6 vertex-hook node filter (sl_shader_chunk_desc.when_node_tag, scene node "tags") and
# SlSurface.object_position: tests/test_vertex_node_tags.c with the tp-tagged test plugin.
add_library(tp_tp-tagged MODULE ${CMAKE_CURRENT_SOURCE_DIR}/plugins/tp_tagged.c)
set_target_properties(tp_tp-tagged PROPERTIES PREFIX "" OUTPUT_NAME tp-tagged
  LIBRARY_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests/plugins/tp-tagged C_VISIBILITY_PRESET hidden)
target_link_libraries(tp_tp-tagged PRIVATE shadelab_sdk)
file(MAKE_DIRECTORY ${PROJECT_BINARY_DIR}/tests/plugins/tp-tagged)
file(CREATE_LINK ${CMAKE_CURRENT_SOURCE_DIR}/plugins/tp_tagged.glsl
     ${PROJECT_BINARY_DIR}/tests/plugins/tp-tagged/tp_tagged.glsl SYMBOLIC)
add_library(tp_tp-tagged-bad MODULE ${CMAKE_CURRENT_SOURCE_DIR}/plugins/tp_tagged.c)
set_target_properties(tp_tp-tagged-bad PROPERTIES PREFIX "" OUTPUT_NAME tp-tagged-bad
  LIBRARY_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests/plugins/tp-tagged-bad C_VISIBILITY_PRESET hidden)
target_link_libraries(tp_tp-tagged-bad PRIVATE shadelab_sdk)
target_compile_definitions(tp_tp-tagged-bad PRIVATE TP_TAGGED_BAD TP_TAGGED_ID="tp-tagged-bad")
sl_add_test(vertex_node_tags SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_vertex_node_tags.c TIMEOUT 120)
target_compile_definitions(test_vertex_node_tags PRIVATE
  TP_TAGGED_PATH="${PROJECT_BINARY_DIR}/tests/plugins/tp-tagged/tp-tagged.so"
  TP_TAGGED_BAD_PATH="${PROJECT_BINARY_DIR}/tests/plugins/tp-tagged-bad/tp-tagged-bad.so")
add_dependencies(test_vertex_node_tags tp_tp-tagged tp_tp-tagged-bad)
