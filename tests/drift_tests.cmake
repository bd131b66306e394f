# Lists with one source, checked: each copy that is generated from it must match it.
# README.md's option table is `shadelab --help-markdown` (core/cli.c's table).
add_test(NAME readme_options
         COMMAND ${PROJECT_SOURCE_DIR}/tools/readme-options.sh --check $<TARGET_FILE:shadelab>
                 ${PROJECT_SOURCE_DIR}/README.md)
set_tests_properties(readme_options PROPERTIES TIMEOUT 60 LABELS drift)
