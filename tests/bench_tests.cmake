# shadelab-bench (tools/bench): metrics, Pareto front and --auto-quality choice on synthetic
# data; a tiny sweep of core.ssaa through the real renderer; the command line end to end.
sl_add_test(bench_metrics SOURCES ${CMAKE_CURRENT_LIST_DIR}/bench_metrics.c LABELS bench)
target_link_libraries(test_bench_metrics PRIVATE shadelab_bench)
sl_add_test(bench_sweep SOURCES ${CMAKE_CURRENT_LIST_DIR}/bench_sweep.c LABELS bench)
target_link_libraries(test_bench_sweep PRIVATE shadelab_bench)

# The command line: two settings, tiny image, tiny reference, outputs in a temporary directory
# (@TMP@, tests/run_in_tmpdir.sh), on the bare scene (the built-in default loads five plugins).
add_test(NAME bench_cli COMMAND ${CMAKE_CURRENT_LIST_DIR}/run_in_tmpdir.sh bench_cli $<TARGET_FILE:shadelab-bench>
         --plugin core --scene ${PROJECT_SOURCE_DIR}/scenes/basic.json --size 32x24 --frames 3 --warmup 1
         --settings core.ssaa=1 --settings core.ssaa=3 --cache @TMP@/cache
         --out @TMP@/core --metric rmse --metric dssim -q)
# Bad input is refused with a message, not a crash.
add_test(NAME bench_cli_bad_plugin COMMAND ${CMAKE_CURRENT_LIST_DIR}/run_in_tmpdir.sh bench_cli_bad_plugin
         $<TARGET_FILE:shadelab-bench> --plugin no-such-plugin --size 16x16 --no-cache --out @TMP@/bad)
add_test(NAME bench_cli_bad_vary COMMAND shadelab-bench --plugin core --vary core.nope=1,2 --list)
set_tests_properties(bench_cli bench_cli_bad_plugin bench_cli_bad_vary PROPERTIES
                     ENVIRONMENT "${SL_TEST_ENV}" TIMEOUT ${SL_HANG_GUARD} LABELS bench)
set_tests_properties(bench_cli_bad_plugin PROPERTIES WILL_FAIL TRUE)
set_tests_properties(bench_cli_bad_vary PROPERTIES PASS_REGULAR_EXPRESSION "not a quality knob of core")

# --orbit end to end on the bare scene: the truth is the orbit's own settings (--orbit-hq ""), so
# the converged still at a captured camera must equal it exactly: the cameras line up.
add_test(NAME bench_cli_orbit COMMAND ${CMAKE_CURRENT_LIST_DIR}/run_in_tmpdir.sh bench_cli_orbit $<TARGET_FILE:shadelab-bench>
         --orbit 1.5 --scene ${PROJECT_SOURCE_DIR}/scenes/basic.json --size 32x24 --orbit-points 2 --orbit-hq ""
         --out @TMP@/orbit -q)
set_tests_properties(bench_cli_orbit PROPERTIES ENVIRONMENT "${SL_TEST_ENV}" TIMEOUT ${SL_HANG_GUARD} LABELS bench
                     PASS_REGULAR_EXPRESSION "frame ms: p50 [0-9.]+  p95 [0-9.]+  p99 [0-9.]+.*mean of 2 frame pairs.*converged still \\([ 0-9]+ f\\): FLIP 0.0000  RMSE 0\n")

# --orbit-variant and --orbit-rounds: with a frame-time budget of 1 ms (the cheapest settings while
# moving) and without, two rounds each, interleaved: each result pools both rounds' 2 pairs, and
# the budget's converged still (its best settings) equals the budget-free still exactly.
add_test(NAME bench_cli_orbit_budget COMMAND ${CMAKE_CURRENT_LIST_DIR}/run_in_tmpdir.sh bench_cli_orbit_budget
         $<TARGET_FILE:shadelab-bench> --orbit 1.5 --scene ${PROJECT_SOURCE_DIR}/scenes/basic.json --size 32x24
         --orbit-points 2 --orbit-hq "" --orbit-variant "core.budget=1" --orbit-variant "" --orbit-rounds 2
         --out @TMP@/orbit -q)
set_tests_properties(bench_cli_orbit_budget PROPERTIES ENVIRONMENT "${SL_TEST_ENV_OPTIMISED}" TIMEOUT ${SL_HANG_GUARD} LABELS bench
                     PASS_REGULAR_EXPRESSION "variant \"core.budget=1\", 2 round\\(s\\):\n[^\n]*\n[^\n]*\n[^\n]*\n[^\n]*mean of 4 frame pairs:\n[^\n]*\n[^\n]*converged still \\([ 0-9]+ f\\): FLIP 0.0000  RMSE 0\n.*mean of 4 frame pairs.*converged still \\([ 0-9]+ f\\): FLIP 0.0000  RMSE 0\n")

# --orbit-passes: every pass timed in every orbit frame, medians pooled over two rounds; the forward
# pass runs in every frame of the orbit, the time outside the passes is reported beside it; the
# CPU time of a frame (pooled too) is reported and positive (under 1 ms on a fast idle machine).
add_test(NAME bench_cli_orbit_passes COMMAND ${CMAKE_CURRENT_LIST_DIR}/run_in_tmpdir.sh bench_cli_orbit_passes
         $<TARGET_FILE:shadelab-bench> --orbit 1 --scene ${PROJECT_SOURCE_DIR}/scenes/basic.json --size 32x24
         --orbit-points 1 --orbit-hq "" --orbit-passes --orbit-rounds 2 --out @TMP@/orbit -q)
set_tests_properties(bench_cli_orbit_passes PROPERTIES ENVIRONMENT "${SL_TEST_ENV}" TIMEOUT ${SL_HANG_GUARD} LABELS bench
                     PASS_REGULAR_EXPRESSION "CPU ms per frame \\(every thread of the process\\): p50 ([1-9][0-9.]*|0\\.[0-9]*[1-9][0-9]*)  mean ([1-9][0-9.]*|0\\.[0-9]*[1-9][0-9]*)\n.*per pass, median ms over the frames it ran in \\(frames\\): outside the passes [0-9.]+ \\([1-9][0-9]*\\), forward [0-9.]+ \\([1-9][0-9]*\\)")
