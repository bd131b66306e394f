# Every relative link in the project's Markdown files resolves to a file and, with #anchor, to a
# heading of that file (tests/doc_links.sh). By hand: tests/doc_links.sh SOURCE_DIR
add_test(NAME doc_links COMMAND ${CMAKE_CURRENT_LIST_DIR}/doc_links.sh ${PROJECT_SOURCE_DIR})
set_tests_properties(doc_links PROPERTIES LABELS docs TIMEOUT ${SL_HANG_GUARD})
