# Extra-credit modules (extras/): built against a fresh install of this tree, as a third party
# builds a plugin, and their own tests run through ctest.
add_test(NAME extras
         COMMAND ${CMAKE_CURRENT_LIST_DIR}/extras.sh ${PROJECT_SOURCE_DIR} ${PROJECT_BINARY_DIR} ${CMAKE_COMMAND})
set_tests_properties(extras PROPERTIES ENVIRONMENT "${SL_TEST_ENV}" TIMEOUT 900 LABELS "extras;sdk")
