# shadelab_add_plugin(NAME SOURCES src.c… [GLSL file.glsl…] [NO_INSTALL])
#
# Builds NAME as a loadable module NAME.so in ${CMAKE_CURRENT_BINARY_DIR}/plugins/NAME/ with its
# GLSL beside it (the plugin's resource directory is the directory of its .so), hides every
# symbol but the entry point, and installs both into <prefix>/lib/shadelab/plugins/NAME/ where
# the viewer finds it by name (--plugin NAME, scene "plugins": ["NAME"]). NO_INSTALL: built only
# (test plugins that a test loads by path).
# GLSL files are symlinked into the build tree, so editing them hot-reloads a running viewer.
#
# One function for every plugin: installed with the SDK (find_package(shadelab) includes it) and
# included by shadelab's own CMakeLists.txt for the bundled plugins. It links the SDK target
# shadelab::sdk, which is the imported target of the installed package and, in shadelab's own
# tree, an alias of shadelab_sdk. Two variables, read when it is called, adapt the layout; a
# third-party build leaves them unset:
#   SHADELAB_PLUGIN_OUTPUT_DIR     where NAME/NAME.so goes (default ${CMAKE_CURRENT_BINARY_DIR}/plugins;
#                                  shadelab's tree: build/plugins, where the viewer finds them)
#   SHADELAB_PLUGIN_TARGET_PREFIX  prefix of the target's name (default none: the target is NAME;
#                                  shadelab's tree: plugin_, e.g. plugin_ggx)
include_guard(GLOBAL)
include(GNUInstallDirs)

function(shadelab_add_plugin name)
  cmake_parse_arguments(P "NO_INSTALL" "" "SOURCES;GLSL" ${ARGN})
  if(NOT P_SOURCES)
    message(FATAL_ERROR "shadelab_add_plugin(${name}): SOURCES is required")
  endif()
  if(DEFINED SHADELAB_PLUGIN_OUTPUT_DIR)
    set(dir "${SHADELAB_PLUGIN_OUTPUT_DIR}/${name}")
  else()
    set(dir "${CMAKE_CURRENT_BINARY_DIR}/plugins/${name}")
  endif()
  set(target "${SHADELAB_PLUGIN_TARGET_PREFIX}${name}")
  add_library(${target} MODULE ${P_SOURCES})
  set_target_properties(${target} PROPERTIES PREFIX "" OUTPUT_NAME ${name}
    LIBRARY_OUTPUT_DIRECTORY "${dir}"
    C_VISIBILITY_PRESET hidden CXX_VISIBILITY_PRESET hidden)
  target_link_libraries(${target} PRIVATE shadelab::sdk)
  if(UNIX AND NOT APPLE)
    target_link_libraries(${target} PRIVATE m)   # libm: C plugins use it; the viewer links it too
  endif()
  file(MAKE_DIRECTORY "${dir}")
  foreach(f ${P_GLSL})
    get_filename_component(abs "${f}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    get_filename_component(fn "${f}" NAME)
    file(CREATE_LINK "${abs}" "${dir}/${fn}" SYMBOLIC COPY_ON_ERROR)
    if(NOT P_NO_INSTALL)
      install(FILES "${abs}" DESTINATION "${CMAKE_INSTALL_LIBDIR}/shadelab/plugins/${name}")
    endif()
  endforeach()
  if(NOT P_NO_INSTALL)
    install(TARGETS ${target} LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}/shadelab/plugins/${name}")
  endif()
endfunction()
