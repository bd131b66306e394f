# glTF 2.0 import (issue 15): fixtures written by the test itself (tests/test_gltf.c), and the
# glTF2 models Debian ships in assimp-testmodels against a committed table of outcomes
# (tests/test_gltf_models.c, tests/data/gltf_models.tsv).
sl_add_test(gltf SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_gltf.c LABELS scene gltf TIMEOUT 120)
sl_add_test(gltf_models SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_gltf_models.c LABELS scene gltf TIMEOUT 120)
