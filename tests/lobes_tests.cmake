# The lobe contract's fallback warning (tests/lobes_fallback.sh): one line per run for each model
# without lobes that an environment or an area light lights (classic phong, skin, dielectric),
# none otherwise. It loads refraction and area-light, which are extras.
if(SL_BUILD_EXTRAS)
  add_test(NAME lobes_fallback COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/run_in_tmpdir.sh lobes_fallback
           ${CMAKE_CURRENT_SOURCE_DIR}/lobes_fallback.sh $<TARGET_FILE:shadelab> @TMP@)
  set_tests_properties(lobes_fallback PROPERTIES ENVIRONMENT "${SL_TEST_ENV}" TIMEOUT ${SL_HANG_GUARD} LABELS architecture)
endif()
