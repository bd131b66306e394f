# shadelab_add_plugin(NAME SOURCES src.c… [GLSL file.glsl…])
#
# Builds NAME as a loadable module NAME.so in ${CMAKE_CURRENT_BINARY_DIR}/plugins/NAME/ with its
# GLSL beside it (the plugin's resource directory is the directory of its .so), hides every
# symbol but the entry point, and installs both into <prefix>/lib/shadelab/plugins/NAME/ where
# the viewer finds it by name (--plugin NAME, scene "plugins": ["NAME"]).
# GLSL files are symlinked into the build tree, so editing them hot-reloads a running viewer.
include_guard(GLOBAL)
include(GNUInstallDirs)

function(shadelab_add_plugin name)
  cmake_parse_arguments(P "" "" "SOURCES;GLSL" ${ARGN})
  if(NOT P_SOURCES)
    message(FATAL_ERROR "shadelab_add_plugin(${name}): SOURCES is required")
  endif()
  set(dir "${CMAKE_CURRENT_BINARY_DIR}/plugins/${name}")
  add_library(${name} MODULE ${P_SOURCES})
  set_target_properties(${name} PROPERTIES PREFIX "" OUTPUT_NAME ${name}
    LIBRARY_OUTPUT_DIRECTORY "${dir}"
    C_VISIBILITY_PRESET hidden CXX_VISIBILITY_PRESET hidden)
  target_link_libraries(${name} PRIVATE shadelab::sdk)
  file(MAKE_DIRECTORY "${dir}")
  foreach(f ${P_GLSL})
    get_filename_component(abs "${f}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    get_filename_component(fn "${f}" NAME)
    file(CREATE_LINK "${abs}" "${dir}/${fn}" SYMBOLIC COPY_ON_ERROR)
    install(FILES "${abs}" DESTINATION "${CMAKE_INSTALL_LIBDIR}/shadelab/plugins/${name}")
  endforeach()
  install(TARGETS ${name} LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}/shadelab/plugins/${name}")
endfunction()
