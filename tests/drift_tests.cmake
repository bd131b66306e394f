# Lists with one source, checked: each copy that is generated from it must match it.
# README.md's option table is `shadelab --help-markdown` (core/cli.c's table), its glTF table
# `shadelab --gltf-markdown` (core/scene/gltf_extensions.c's lists).
add_test(NAME readme_options
         COMMAND ${PROJECT_SOURCE_DIR}/tools/readme-options.sh --check $<TARGET_FILE:shadelab>
                 ${PROJECT_SOURCE_DIR}/README.md)
set_tests_properties(readme_options PROPERTIES TIMEOUT ${SL_HANG_GUARD} LABELS drift)

# docs/gallery.md is made from the scenes' metadata (tools/gallery.sh names no scene or plugin):
# every scene's "gallery" entries are well-formed and the plan of images has no clash.
add_test(NAME gallery_plan COMMAND ${PROJECT_SOURCE_DIR}/tools/gallery.sh --plan ${PROJECT_BINARY_DIR})
set_tests_properties(gallery_plan PROPERTIES ENVIRONMENT "${SL_TEST_ENV}" TIMEOUT ${SL_HANG_GUARD} LABELS drift)
