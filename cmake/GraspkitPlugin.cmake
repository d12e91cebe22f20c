# graspkit_add_plugin(<target> <source>...)
# A graspkit plugin: a MODULE library named <target>.so that links graspkit::engine and exports
# only its graspkit_plugin_v1 symbol. Inside the graspkit build it lands in the plugin folder
# beside libgraspkit (found with no environment variable); out of tree it stays in the build
# folder and is found through GRASPKIT_PLUGIN_PATH. `cmake --install` puts it in
# <libdir>/graspkit/plugins.
include_guard(GLOBAL)
include(GNUInstallDirs)

function(graspkit_add_plugin target)
  add_library(${target} MODULE ${ARGN})
  target_link_libraries(${target} PRIVATE graspkit::engine)
  set_target_properties(${target} PROPERTIES
    PREFIX ""
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
  if(GRASPKIT_PLUGIN_OUTPUT_DIR)
    set_target_properties(${target} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${GRASPKIT_PLUGIN_OUTPUT_DIR})
  endif()
  install(TARGETS ${target} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/graspkit/plugins)
endfunction()
