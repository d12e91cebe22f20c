# `graspkit --version` prints the version the project declares (CMakeLists.txt's project()) and
# exits 0, with no subcommand needed.

file(READ ${SOURCE_DIR}/CMakeLists.txt top)
string(REGEX MATCH "project\\(graspkit VERSION ([0-9.]+)" _ "${top}")
set(declared "${CMAKE_MATCH_1}")
if(declared STREQUAL "")
  message(FATAL_ERROR "no version in ${SOURCE_DIR}/CMakeLists.txt")
endif()
execute_process(COMMAND ${GRASPKIT} --version OUTPUT_VARIABLE out ERROR_VARIABLE err
                RESULT_VARIABLE rc)
string(STRIP "${out}" out)
if(NOT rc EQUAL 0 OR NOT out STREQUAL "graspkit ${declared}")
  message(FATAL_ERROR "graspkit --version: exit ${rc}, printed '${out}' (stderr '${err}'), "
                      "expected 'graspkit ${declared}'")
endif()
