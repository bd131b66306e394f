# Scene subsystem tests (core/scene/): loader, primitives, tangents, mesh import.
sl_add_test(scene SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_scene.c LABELS scene)
sl_add_test(scene_geometry SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_scene_geometry.c LABELS scene)
sl_add_test(scene_import SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_scene_import.c LABELS scene)
