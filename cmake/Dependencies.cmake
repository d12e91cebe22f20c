# Every dependency comes from a Debian package (see README: the install step).
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(tinyxml2 REQUIRED)
find_package(fmt REQUIRED)
find_package(spdlog REQUIRED)
find_package(CLI11 QUIET)
find_package(nlohmann_json 3 REQUIRED)
find_package(Coin CONFIG REQUIRED)
find_package(assimp REQUIRED)
find_package(urdfdom REQUIRED)
find_package(fcl REQUIRED)
find_package(embree 3 REQUIRED)
find_package(Qhull REQUIRED)
find_package(HDF5 REQUIRED COMPONENTS C)  # grasp dataset files (io/grasp_dataset_file)
find_package(PNG REQUIRED)
find_package(TinyGLTF REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(LUA REQUIRED IMPORTED_TARGET lua5.4)
if(GRASPKIT_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(GRASPKIT_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()

# Siconos numerics solves the dynamics' friction-contact problems. Debian ships its CMake package
# with the kernel and control libraries' targets, which libsiconos-numerics-dev alone does not
# install, so the library and headers are found directly.
find_path(SICONOS_NUMERICS_INCLUDE_DIR FrictionContactProblem.h PATH_SUFFIXES siconos/numerics
          REQUIRED)
find_library(SICONOS_NUMERICS_LIBRARY siconos_numerics REQUIRED)
if(NOT TARGET SiconosNumerics::numerics)
  add_library(SiconosNumerics::numerics UNKNOWN IMPORTED)
  get_filename_component(_siconos_root ${SICONOS_NUMERICS_INCLUDE_DIR} DIRECTORY)
  set_target_properties(SiconosNumerics::numerics PROPERTIES
    IMPORTED_LOCATION ${SICONOS_NUMERICS_LIBRARY}
    INTERFACE_INCLUDE_DIRECTORIES "${SICONOS_NUMERICS_INCLUDE_DIR};${_siconos_root}")
endif()
