# The module rule (docs/design-notes.md, "Where things go"): no plugin, extra or tool includes,
# compiles or calls another module's private code, and the core depends on none of them; cycles
# between the core's modules are reported (not failed, yet). It reads the sources and this build
# tree's objects (nm), so it runs after the build. By hand: tests/module_rule.sh SOURCE_DIR BUILD_DIR
add_test(NAME module_rule COMMAND ${CMAKE_CURRENT_LIST_DIR}/module_rule.sh ${PROJECT_SOURCE_DIR} ${PROJECT_BINARY_DIR})
set_tests_properties(module_rule PROPERTIES LABELS architecture TIMEOUT ${SL_HANG_GUARD} ENVIRONMENT "NM=${CMAKE_NM}")
# The model rule (tests/model_rule.sh): no module (plugin, extra, SDK example, tool, the core and
# its shaders) names a shading model it does not register;
# its self-test plants an offence and expects it found.
add_test(NAME model_rule COMMAND ${CMAKE_CURRENT_LIST_DIR}/model_rule.sh ${PROJECT_SOURCE_DIR})
add_test(NAME model_rule_self_test COMMAND ${CMAKE_CURRENT_LIST_DIR}/model_rule.sh --self-test)
set_tests_properties(model_rule model_rule_self_test PROPERTIES LABELS architecture TIMEOUT ${SL_HANG_GUARD})
