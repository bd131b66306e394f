# Declared pass dependencies (pass.h sl_depends, ABI 1.8): which passes re-run after each kind of
# change (tp-deps: one pass per dependency), and frames with skipped passes against fresh starts.
sl_add_test_plugin(tp-deps DIR ${SL_TP_DIR} PREFIX tp_ SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/plugins/tp_deps.c)
sl_add_test(pass_skip SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_pass_skip.c TIMEOUT ${SL_HANG_GUARD})
target_compile_definitions(test_pass_skip PRIVATE SL_TEST_PLUGIN_DIR="${SL_TP_DIR}")
target_compile_definitions(test_pass_skip PRIVATE SL_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
add_dependencies(test_pass_skip tp_tp-deps tp_tp-good plugin_sss plugin_spotlight-shadow plugin_tonemap plugin_ggx
                 plugin_envmap plugin_normal-map plugin_aa plugin_ssao)
