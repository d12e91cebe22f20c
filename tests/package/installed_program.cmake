# The installed program as a user runs it after `cmake --install` (README, "Installing"):
#   1. share/graspkit holds the models, docs and examples;
#   2. an installed example runs with no --root and prints what the same example prints from the
#      checkout with --root models;
#   3. the plugin search path is the install's own folder, and follows the install when its
#      prefix is moved (no folder fixed at configure time).
# Arguments: -DBUILD_DIR (this build), -DSOURCE_DIR, -DWORK_DIR, -DGRASPKIT (the build's program).

set(install ${WORK_DIR}/install)
set(moved ${WORK_DIR}/moved)
include(${CMAKE_CURRENT_LIST_DIR}/run.cmake)
fresh_install_test()

# 1.
run("cmake --install" COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${install})
foreach(file models/worlds/default.xml models/robots/bh8/bh8.xml examples/autograsp_mug.lua
             examples/README.md docs/lua.md README.md)
  if(NOT EXISTS ${install}/share/graspkit/${file})
    message(FATAL_ERROR "the install lacks share/graspkit/${file}")
  endif()
endforeach()

# 2.
run("the example from the checkout" COMMAND ${GRASPKIT} run ${SOURCE_DIR}/examples/autograsp_mug.lua
    --root ${SOURCE_DIR}/models WORKING_DIRECTORY ${SOURCE_DIR})
set(expected "${out}")
run("the installed example" COMMAND ${install}/bin/graspkit run
    ${install}/share/graspkit/examples/autograsp_mug.lua WORKING_DIRECTORY ${WORK_DIR})
if(NOT out STREQUAL expected OR NOT out MATCHES "epsilon")
  message(FATAL_ERROR "the installed example printed\n${out}\nthe checkout's\n${expected}")
endif()
# A world that names its models relative to the root, from anywhere.
file(WRITE ${WORK_DIR}/load.lua "print(#graspkit.load_world('worlds/default.xml'):bodies())\n")
run("a model path relative to the installed root" COMMAND ${install}/bin/graspkit run
    ${WORK_DIR}/load.lua)
if(NOT out STREQUAL "2\n")
  message(FATAL_ERROR "worlds/default.xml from the installed root: '${out}'")
endif()

# 3.
function(expect_search_path prefix)
  run("plugins --json" COMMAND ${prefix}/bin/graspkit plugins --json)
  string(JSON count LENGTH "${out}" search_path)
  string(JSON first GET "${out}" search_path 0)
  file(REAL_PATH ${first} first)
  file(REAL_PATH ${prefix}/lib/graspkit/plugins own)
  if(NOT count EQUAL 1 OR NOT first STREQUAL own)
    message(FATAL_ERROR "the search path of ${prefix} is not its own plugin folder alone:\n${out}")
  endif()
  if(NOT out MATCHES "\"simann\"")
    message(FATAL_ERROR "the install at ${prefix} finds no simann planner:\n${out}")
  endif()
endfunction()
expect_search_path(${install})
file(RENAME ${install} ${moved})
expect_search_path(${moved})
