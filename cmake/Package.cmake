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
