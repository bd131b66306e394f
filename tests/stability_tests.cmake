# Stability of the core in its known failure regions (docs/stability.md lists each case).
sl_add_test(stability_core SOURCES ${CMAKE_CURRENT_LIST_DIR}/stability_core.c LABELS stability)
