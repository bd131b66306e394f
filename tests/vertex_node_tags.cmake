# ABI 1.6 vertex-hook node filter (sl_shader_chunk_desc.when_node_tag, scene node "tags") and
# SlSurface.object_position: tests/test_vertex_node_tags.c with the tp-tagged test plugin.
sl_add_test_plugin(tp-tagged DIR ${PROJECT_BINARY_DIR}/tests/plugins PREFIX tp_
                   SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/plugins/tp_tagged.c GLSL plugins/tp_tagged.glsl)
sl_add_test_plugin(tp-tagged-bad DIR ${PROJECT_BINARY_DIR}/tests/plugins PREFIX tp_
                   SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/plugins/tp_tagged.c)
target_compile_definitions(tp_tp-tagged-bad PRIVATE TP_TAGGED_BAD TP_TAGGED_ID="tp-tagged-bad")
sl_add_test(vertex_node_tags SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_vertex_node_tags.c TIMEOUT ${SL_HANG_GUARD})
target_compile_definitions(test_vertex_node_tags PRIVATE
  TP_TAGGED_PATH="${PROJECT_BINARY_DIR}/tests/plugins/tp-tagged/tp-tagged.so"
  TP_TAGGED_BAD_PATH="${PROJECT_BINARY_DIR}/tests/plugins/tp-tagged-bad/tp-tagged-bad.so")
add_dependencies(test_vertex_node_tags tp_tp-tagged tp_tp-tagged-bad)
