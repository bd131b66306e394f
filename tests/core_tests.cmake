# Core tests: closed-form renders, GLSL unit tests, bad input, loader failure paths and the
# structural zero-cost checks. Test plugins are built from tests/plugins/test_plugin.c in
# variants that each exercise one loader path.
set(SL_TP_DIR ${PROJECT_BINARY_DIR}/tests/plugins)

add_library(tp_dep SHARED ${CMAKE_CURRENT_SOURCE_DIR}/plugins/tp_dep.c)
set_target_properties(tp_dep PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${SL_TP_DIR}/deps)

function(sl_test_plugin name glsl)
  cmake_parse_arguments(T "NO_RPATH" "" "DEFS;LIBS" ${ARGN})
  sl_add_test_plugin(${name} DIR ${SL_TP_DIR} PREFIX tp_ SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/plugins/test_plugin.c
                     GLSL plugins/${glsl} plugins/tp_gain.frag)
  if(T_NO_RPATH)
    set_target_properties(tp_${name} PROPERTIES SKIP_BUILD_RPATH TRUE)
  endif()
  target_link_libraries(tp_${name} PRIVATE ${T_LIBS})
  target_compile_definitions(tp_${name} PRIVATE TP_ID="${name}" TP_MODEL="${name}-model"
                             TP_GLSL="${glsl}" ${T_DEFS})
  set(SL_TEST_PLUGINS ${SL_TEST_PLUGINS} tp_${name} PARENT_SCOPE)
endfunction()

sl_test_plugin(tp-good test_plugin.glsl)
sl_test_plugin(tp-other test_plugin.glsl)
sl_test_plugin(tp-abi-major test_plugin.glsl DEFS SL_ABI_MAJOR=2)
sl_test_plugin(tp-abi-minor test_plugin.glsl DEFS SL_ABI_MINOR=99)
sl_test_plugin(tp-no-entry test_plugin.glsl DEFS TP_NO_ENTRY)
sl_test_plugin(tp-undefined test_plugin.glsl DEFS TP_UNDEFINED_SYMBOL)
sl_test_plugin(tp-missing-dep test_plugin.glsl NO_RPATH DEFS TP_DEPENDENCY LIBS tp_dep)
sl_test_plugin(tp-dup-model test_plugin.glsl DEFS TP_DUP_MODEL)
sl_test_plugin(tp-bad-glsl test_plugin_bad.glsl)
sl_test_plugin(tp-fail-create test_plugin.glsl DEFS TP_FAIL_CREATE)
sl_test_plugin(tp-requires test_plugin.glsl DEFS TP_REQUIRES="tp-nonexistent")
sl_test_plugin(tp-requires-good test_plugin.glsl DEFS TP_REQUIRES="tp-good")
sl_test_plugin(tp-conflicts test_plugin.glsl DEFS TP_CONFLICTS="tp-good")
# material inputs: a key's input the descriptor does not list, a listed one no key takes, both agreeing
sl_test_plugin(tp-input-unlisted test_plugin.glsl DEFS TP_KEY_INPUT="tp_input")
sl_test_plugin(tp-input-unclaimed test_plugin.glsl DEFS TP_LISTED_INPUT="tp_input")
sl_test_plugin(tp-input-agreed test_plugin.glsl DEFS TP_KEY_INPUT="tp_input" TP_LISTED_INPUT="tp_input")
sl_test_plugin(tp-model-unlisted test_plugin.glsl DEFS TP_UNLISTED_MODEL)
sl_test_plugin(tp-model-unprovided test_plugin.glsl DEFS TP_UNPROVIDED_MODEL)
sl_test_plugin(tp-bad-gate test_plugin.glsl DEFS TP_BAD_GATE)
# a model that masks facing-away normals itself (SL_CHUNK_MASKS_FACING_AWAY; normal-map's test)
sl_test_plugin(tp-masks test_plugin.glsl DEFS TP_MASKS_FACING_AWAY)

foreach(t core_render core_glsl core_bad_input core_plugins core_zero_cost)
  sl_add_test(${t} SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_${t}.c)
  target_compile_definitions(test_${t} PRIVATE SL_TEST_PLUGIN_DIR="${SL_TP_DIR}"
                             SL_SCENES_DIR="${PROJECT_SOURCE_DIR}/scenes")
  add_dependencies(test_${t} ${SL_TEST_PLUGINS})
endforeach()

# sl_program_uniform's cache of uniform locations against GL's own answers.
sl_add_test(program_uniform SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_program_uniform.c)

# The command line end to end: the bundled scenes render headless, and bad input exits
# non-zero with the cause named.
add_test(NAME cli_scenes COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/run_in_tmpdir.sh cli_scenes
         ${CMAKE_CURRENT_SOURCE_DIR}/cli_scenes.sh $<TARGET_FILE:shadelab> ${PROJECT_SOURCE_DIR}/scenes @TMP@)
set_tests_properties(cli_scenes PROPERTIES ENVIRONMENT "${SL_TEST_ENV}" TIMEOUT ${SL_HANG_GUARD})

# Pass order by stage value, not load order; dependencies switch off with what they need.
sl_add_test(pass_order SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_pass_order.c)
target_compile_definitions(test_pass_order PRIVATE SL_TEST_PLUGIN_DIR="${SL_TP_DIR}")
add_dependencies(test_pass_order ${SL_TEST_PLUGINS})

# --explain lists vertex hooks with the fragment chunks of each material's program.
add_test(NAME explain_vertex_hooks COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/explain_vertex_hooks.sh $<TARGET_FILE:shadelab>)
set_tests_properties(explain_vertex_hooks PROPERTIES ENVIRONMENT "${SL_TEST_ENV};SHADELAB_PLUGIN_PATH=${SL_TP_DIR}" TIMEOUT ${SL_HANG_GUARD})

# --turntable: the orbit's cameras against closed forms (seamless loop), frame names; and the
# command line end to end (files, frames that differ, frame k depends only on its angle, ffmpeg
# present or missing).
sl_add_test(turntable SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_turntable.c)
add_test(NAME cli_turntable COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/run_in_tmpdir.sh cli_turntable
         ${CMAKE_CURRENT_SOURCE_DIR}/cli_turntable.sh $<TARGET_FILE:shadelab> $<TARGET_FILE:sl-imgdiff> @TMP@)
set_tests_properties(cli_turntable PROPERTIES ENVIRONMENT "${SL_TEST_ENV}" TIMEOUT ${SL_HANG_GUARD})

# Lazy program creation (issue 19's cold start): programs of passes that never run are not
# compiled; those that do run are (the -v list of programs built).
add_test(NAME cli_lazy_programs COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/run_in_tmpdir.sh cli_lazy_programs
         ${CMAKE_CURRENT_SOURCE_DIR}/cli_lazy_programs.sh $<TARGET_FILE:shadelab> ${PROJECT_SOURCE_DIR}/scenes @TMP@)
set_tests_properties(cli_lazy_programs PROPERTIES ENVIRONMENT "${SL_TEST_ENV}" TIMEOUT ${SL_HANG_GUARD})
# A warm start reuses what the start before it built: far less start-up CPU, and the plugins'
# own caches hit (measured with --stats and -v; cli_warm_start.sh says why CPU time and the margin).
add_test(NAME cli_warm_start COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/run_in_tmpdir.sh cli_warm_start
         ${CMAKE_CURRENT_SOURCE_DIR}/cli_warm_start.sh $<TARGET_FILE:shadelab> ${PROJECT_SOURCE_DIR}/scenes @TMP@)
set_tests_properties(cli_warm_start PROPERTIES ENVIRONMENT "${SL_TEST_ENV}" TIMEOUT ${SL_HANG_GUARD})
add_test(NAME cli_lazy_oiio COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/run_in_tmpdir.sh cli_lazy_oiio
         ${CMAKE_CURRENT_SOURCE_DIR}/cli_lazy_oiio.sh $<TARGET_FILE:shadelab> ${PROJECT_SOURCE_DIR}/scenes @TMP@)
set_tests_properties(cli_lazy_oiio PROPERTIES ENVIRONMENT "${SL_TEST_ENV}" TIMEOUT ${SL_HANG_GUARD})

# Headless stills stop when they are done (core/still.h): converged (no display value changes by
# 1/255), or the budget ran out; a scene with hard edges runs its still to the end.
sl_add_test(still_stop SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_still_stop.c)
# Frustum culling: instances outside the view cost no draw call and change no pixel; one on the
# view's edge is drawn.
sl_add_test(frustum_cull SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_frustum_cull.c)
# The frame-time budget's controller on synthetic cost models (no GL, no timing).
sl_add_test(budget SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_budget.c TIMEOUT ${SL_HANG_GUARD} OPTIMISED_SHADERS)
# ... and in a real scene: the window opens as a still, even where a plugin's own light (envmap's
# sky sun) comes on as the first frame begins, and an edit switching that light is one motion frame.
sl_add_test(budget_motion SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_budget_motion.c OPTIMISED_SHADERS)

# 100 000 overlapping blended quads under TAA: the still completes, each cell's colour is the
# closed form of its layers.
sl_add_test(blend_layers SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_blend_layers.c)

# Levels of detail by projected size (core.lod_pixels): meshoptimizer's levels, the choice in
# closed form, a far sphere drawn with fewer triangles and a near one in full.
sl_add_test(lod SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_lod.c)
