# Scene subsystem tests (core/scene/): loader, primitives, tangents, mesh import.
sl_add_test(scene SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_scene.c LABELS scene)
sl_add_test(scene_geometry SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_scene_geometry.c LABELS scene)
sl_add_test(scene_import SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_scene_import.c LABELS scene)
# The project's OBJ reader vs the assimp import it replaced, and hostile OBJ files (issue 14).
sl_add_test(obj_reader SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_obj_reader.c LABELS "scene;hostile")
# import_file: one file through one reader (obj, assimp), for tools/import/bench_import.sh
add_executable(import_file ${CMAKE_CURRENT_LIST_DIR}/import_file.c)
target_link_libraries(import_file PRIVATE shadelab_core)
set_target_properties(import_file PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tools)
