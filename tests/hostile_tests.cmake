# Hostile input (issue 14): bounded time, a message naming the input, outputs left untouched.
add_test(NAME hostile_input COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/hostile_input.sh $<TARGET_FILE:shadelab>
                                    $<TARGET_FILE:shadelab-bench> $<TARGET_FILE:shadelab-cube>)
set_tests_properties(hostile_input PROPERTIES ENVIRONMENT "${SL_TEST_ENV}" TIMEOUT ${SL_HANG_GUARD} LABELS hostile)
sl_add_test(hostile_values SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_hostile_values.c LABELS hostile)
target_include_directories(test_hostile_values PRIVATE ${PROJECT_SOURCE_DIR}/core)
