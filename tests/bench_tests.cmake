# shadelab-bench (tools/bench): metrics, Pareto front and --auto-quality choice on synthetic
# data; a tiny sweep of core.ssaa through the real renderer; the command line end to end.
sl_add_test(bench_metrics SOURCES ${CMAKE_CURRENT_LIST_DIR}/bench_metrics.c LABELS bench)
target_link_libraries(test_bench_metrics PRIVATE shadelab_bench)
sl_add_test(bench_sweep SOURCES ${CMAKE_CURRENT_LIST_DIR}/bench_sweep.c LABELS bench)
target_link_libraries(test_bench_sweep PRIVATE shadelab_bench)

# The command line: two settings, tiny image, tiny reference, outputs under the build dir.
set(SL_BENCH_CLI_DIR ${PROJECT_BINARY_DIR}/bench-cli-test)
add_test(NAME bench_cli COMMAND shadelab-bench --plugin core --size 32x24 --frames 3 --warmup 1
         --settings core.ssaa=1 --settings core.ssaa=3 --cache ${SL_BENCH_CLI_DIR}/cache
         --out ${SL_BENCH_CLI_DIR}/core --metric rmse --metric dssim -q
         WORKING_DIRECTORY ${PROJECT_BINARY_DIR})
# Bad input is refused with a message, not a crash.
add_test(NAME bench_cli_bad_plugin COMMAND shadelab-bench --plugin no-such-plugin --size 16x16 --no-cache
         --out ${SL_BENCH_CLI_DIR}/bad)
add_test(NAME bench_cli_bad_vary COMMAND shadelab-bench --plugin core --vary core.nope=1,2 --list)
set_tests_properties(bench_cli bench_cli_bad_plugin bench_cli_bad_vary PROPERTIES
                     ENVIRONMENT "${SL_TEST_ENV}" TIMEOUT 300 LABELS bench)
set_tests_properties(bench_cli_bad_plugin PROPERTIES WILL_FAIL TRUE)
set_tests_properties(bench_cli_bad_vary PROPERTIES PASS_REGULAR_EXPRESSION "not a quality knob of core")
