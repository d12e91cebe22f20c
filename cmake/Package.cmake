# The CMake package `cmake --install` writes to <libdir>/cmake/graspkit: find_package(graspkit)
# gives the imported target graspkit::engine and the function graspkit_add_plugin().
include(CMakePackageConfigHelpers)
include(GNUInstallDirs)

set(GRASPKIT_PACKAGE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/graspkit)

install(EXPORT graspkitTargets NAMESPACE graspkit:: DESTINATION ${GRASPKIT_PACKAGE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/graspkitConfig.cmake.in
  ${PROJECT_BINARY_DIR}/graspkitConfig.cmake
  INSTALL_DESTINATION ${GRASPKIT_PACKAGE_DIR})
# The plugin ABI can change within a major version only by bumping GRASPKIT_PLUGIN_ABI_VERSION,
# which the loader checks; the C++ API follows semantic versioning.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/graspkitConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/graspkitConfig.cmake
              ${PROJECT_BINARY_DIR}/graspkitConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/GraspkitPlugin.cmake
        DESTINATION ${GRASPKIT_PACKAGE_DIR})

# pkg-config files for hosts built without CMake: graspkit (the C++ engine) and graspkit-c (the C
# ABI). The prefix is the one given to `cmake --install --prefix`, read when installing.
foreach(pc graspkit graspkit-c)
  configure_file(${PROJECT_SOURCE_DIR}/cmake/pkgconfig/${pc}.pc.in ${PROJECT_BINARY_DIR}/${pc}.pc.in2 @ONLY)
endforeach()
install(CODE "
  foreach(pc graspkit graspkit-c)
    file(READ \"${PROJECT_BINARY_DIR}/\${pc}.pc.in2\" text)
    string(REPLACE \"${CMAKE_INSTALL_PREFIX}\" \"\${CMAKE_INSTALL_PREFIX}\" text \"\${text}\")
    file(WRITE \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR}/pkgconfig/\${pc}.pc\" \"\${text}\")
  endforeach()
")

# The project's models, docs and examples in <datadir>/graspkit, laid out as in the checkout
# (examples/ beside models/), so that the examples run from an install as the README shows them
# and an installed graspkit defaults its model root to share/graspkit/models.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/models ${PROJECT_SOURCE_DIR}/docs ${PROJECT_SOURCE_DIR}/examples
        DESTINATION ${CMAKE_INSTALL_DATADIR}/graspkit)
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DATADIR}/graspkit)
