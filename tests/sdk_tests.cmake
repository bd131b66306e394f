# SDK for third parties (issue 3): install, out-of-tree example, ABI refusals.
# sl-imgdiff: image comparison with a stated tolerance, for the shell-driven tests.
add_executable(sl-imgdiff ${CMAKE_CURRENT_LIST_DIR}/sdk_imgdiff.c)
target_link_libraries(sl-imgdiff PRIVATE shadelab_core)

# Installs into a temporary prefix and builds sdk/example against it (needs the whole build).
add_test(NAME sdk_install
         COMMAND ${CMAKE_CURRENT_LIST_DIR}/sdk_install.sh ${PROJECT_SOURCE_DIR} ${PROJECT_BINARY_DIR}
                 $<TARGET_FILE:sl-imgdiff> ${CMAKE_COMMAND})
set_tests_properties(sdk_install PROPERTIES ENVIRONMENT "${SL_TEST_ENV}" TIMEOUT ${SL_HANG_GUARD} LABELS sdk)

# The public headers compile as C++20 (`requires` is a keyword there): a build-time check.
add_executable(sdk_cxx20 ${CMAKE_CURRENT_LIST_DIR}/sdk_cxx20.cpp)
target_include_directories(sdk_cxx20 PRIVATE ${PROJECT_SOURCE_DIR}/sdk/include)
set_target_properties(sdk_cxx20 PROPERTIES CXX_STANDARD 20 CXX_STANDARD_REQUIRED ON CXX_EXTENSIONS OFF)

# <shadelab/matrix.h>: the 4x4 inverse plugins share, against closed forms.
sl_add_test(sdk_matrix SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_sdk_matrix.c)
