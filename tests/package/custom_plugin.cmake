# The installed package, used as a plugin author would (examples/custom_robot_plugin/README.md):
#   1. `cmake --install` this build into WORK_DIR/install;
#   2. configure and build examples/custom_robot_plugin in a separate folder against it
#      (find_package(graspkit), graspkit_add_plugin);
#   3. the INSTALLED CLI finds the project's own plugins with no environment variable, and the
#      example's plugin through GRASPKIT_PLUGIN_PATH; without it, the error names the unknown
#      type and the search path;
#   4. the example's host program (C++ API) checks the plugin's robot type, closed-form IK and
#      quality measure against hand-computed values.
# Arguments: -DBUILD_DIR (this build), -DSOURCE_DIR, -DWORK_DIR, -DGENERATOR, -DCXX_COMPILER,
# -DCOMPILER_LAUNCHER, -DSANITIZE (the GRASPKIT_SANITIZE of this build).

set(install ${WORK_DIR}/install)
set(example_build ${WORK_DIR}/build-example)
set(example ${SOURCE_DIR}/examples/custom_robot_plugin)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

include(${CMAKE_CURRENT_LIST_DIR}/run.cmake)

# 1. The install.
run("cmake --install" COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${install})
foreach(file bin/graspkit include/graspkit/plugin/plugin.hpp include/graspkit/plugin/registry.hpp
             include/graspkit/io/graspit/robot_file.hpp lib/cmake/graspkit/graspkitConfig.cmake
             lib/cmake/graspkit/graspkitConfigVersion.cmake lib/cmake/graspkit/graspkitTargets.cmake
             lib/cmake/graspkit/GraspkitPlugin.cmake lib/graspkit/plugins/m7.so)
  if(NOT EXISTS ${install}/${file})
    message(FATAL_ERROR "the install lacks ${file}")
  endif()
endforeach()
# Only Eigen may reach users' compile and link lines: the engine's private dependencies stay
# inside libgraspkit.so. (CMake still lists them in IMPORTED_LINK_DEPENDENT_LIBRARIES, a hint
# for the linker's -rpath-link that needs none of them found; the example below configures
# without them.)
file(STRINGS ${install}/lib/cmake/graspkit/graspkitTargets.cmake interface REGEX "INTERFACE_")
# graspkit::lua passes on graspkit::engine alone (Lua stays inside libgraspkit_lua.so);
# graspkit::c passes on nothing.
foreach(line ${interface})
  if(line MATCHES "INTERFACE_LINK_LIBRARIES" AND NOT line MATCHES "INTERFACE_LINK_LIBRARIES \"(Eigen3::Eigen|graspkit::engine)\"")
    message(FATAL_ERROR "an installed graspkit target passes on more than Eigen: ${line}")
  endif()
endforeach()
if(NOT interface MATCHES "INTERFACE_LINK_LIBRARIES")
  message(FATAL_ERROR "graspkit::engine does not pass on Eigen")
endif()
set(graspkit ${install}/bin/graspkit)

# 2. The example, in its own build folder, against the install only. A sanitizer build of
# graspkit needs the same instrumentation in the host program (the ASan runtime must come first).
set(example_options -DCMAKE_PREFIX_PATH=${install} -DCMAKE_BUILD_TYPE=RelWithDebInfo)
if(GENERATOR)
  list(APPEND example_options -G ${GENERATOR})
endif()
if(CXX_COMPILER)
  list(APPEND example_options -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
endif()
if(COMPILER_LAUNCHER)
  list(APPEND example_options -DCMAKE_CXX_COMPILER_LAUNCHER=${COMPILER_LAUNCHER})
endif()
if(SANITIZE)
  set(flags "-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined")
  list(APPEND example_options "-DCMAKE_CXX_FLAGS=${flags}"
       "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined"
       "-DCMAKE_MODULE_LINKER_FLAGS=-fsanitize=address,undefined")
endif()
run("configuring the example" COMMAND ${CMAKE_COMMAND} -S ${example} -B ${example_build} ${example_options})
run("building the example" COMMAND ${CMAKE_COMMAND} --build ${example_build})
if(NOT EXISTS ${example_build}/gripper3.so)
  message(FATAL_ERROR "the example built no ${example_build}/gripper3.so")
endif()

# 3a. The installed CLI with no environment variable finds the installed plugins beside its
# installed libgraspkit: the gripper file retyped as M7 (whose type accepts any structure).
file(READ ${example}/models/gripper3/gripper3.xml gripper)
file(COPY ${example}/models/gripper3/iv DESTINATION ${WORK_DIR}/models)
string(REPLACE "type=\"ThreeFingerGripper\"" "type=\"M7\"" as_m7 "${gripper}")
file(WRITE ${WORK_DIR}/models/as_m7.xml "${as_m7}")
run("installed graspkit info on an M7 robot" COMMAND ${CMAKE_COMMAND} -E env --unset=GRASPKIT_PLUGIN_PATH
    ${graspkit} info ${WORK_DIR}/models/as_m7.xml)
if(NOT out MATCHES "type M7 from plugin m7 [0-9.]+ \\(${install}/lib/graspkit/plugins/m7.so\\)")
  message(FATAL_ERROR "the installed CLI did not use its installed m7 plugin:\n${out}")
endif()

# 3b. The example's plugin through GRASPKIT_PLUGIN_PATH.
set(model ${example}/models/gripper3/gripper3.xml)
run("graspkit info with GRASPKIT_PLUGIN_PATH" COMMAND ${CMAKE_COMMAND} -E env GRASPKIT_PLUGIN_PATH=${example_build}
    ${graspkit} info ${model})
if(NOT out MATCHES "robot gripper3 \\(type ThreeFingerGripper\\): 1 DOFs, 3 chains"
   OR NOT out MATCHES "type ThreeFingerGripper from plugin gripper3 1.0.0 \\(${example_build}/gripper3.so\\)")
  message(FATAL_ERROR "graspkit info does not name the custom type and its plugin:\n${out}")
endif()
# At DOF 0 finger 0's frame is at its chain base (0, 50, 1) (gripper3.xml); at d0 = 20 it has
# moved 20 mm towards the palm axis: (0, 30, 1).
run("graspkit info --dofs 20" COMMAND ${CMAKE_COMMAND} -E env GRASPKIT_PLUGIN_PATH=${example_build}
    ${graspkit} info ${model} --dofs 20)
if(NOT out MATCHES "gripper3_chain0_link0 +t \\[-?0.0000 30.0000 1.0000\\]")
  message(FATAL_ERROR "finger 0 is not at (0, 30, 1) at d0 = 20:\n${out}")
endif()

# 3c. Without the variable the type is unknown: the error names it, the file and where the
# loader looked.
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=GRASPKIT_PLUGIN_PATH ${graspkit} info ${model}
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(rc EQUAL 0)
  message(FATAL_ERROR "a ThreeFingerGripper loaded with no plugin for it:\n${out}")
endif()
if(NOT err MATCHES "gripper3.xml:[0-9]+: <robot>: unknown robot type 'ThreeFingerGripper'"
   OR NOT err MATCHES "plugin search path: [^\n]*${install}/lib/graspkit/plugins")
  message(FATAL_ERROR "the error does not name the type, the file and the search path:\n${err}")
endif()

# 3d. The plugin's configure() refuses a gripper without its three fingers, naming the file.
string(FIND "${gripper}" "<chain>" last_chain REVERSE)
string(FIND "${gripper}" "<approachDirection>" approach)
string(SUBSTRING "${gripper}" 0 ${last_chain} head)
string(SUBSTRING "${gripper}" ${approach} -1 tail)
file(WRITE ${WORK_DIR}/models/two_fingers.xml "${head}${tail}")
execute_process(COMMAND ${CMAKE_COMMAND} -E env GRASPKIT_PLUGIN_PATH=${example_build}
                        ${graspkit} info ${WORK_DIR}/models/two_fingers.xml
                ERROR_VARIABLE err RESULT_VARIABLE rc)
if(rc EQUAL 0 OR NOT err MATCHES "two_fingers.xml.*ThreeFingerGripper has 1 DOF and 3 chains, this model has 1 and 2")
  message(FATAL_ERROR "a two-finger ThreeFingerGripper was accepted (${rc}):\n${err}")
endif()

# 4. The host program through the C++ API.
run("load_custom_robot" COMMAND ${CMAKE_COMMAND} -E env GRASPKIT_PLUGIN_PATH=${example_build}
    ${example_build}/load_custom_robot ${model} ${example}/models/gripper3_can.xml)
foreach(expected
    "robot gripper3: type ThreeFingerGripper from plugin gripper3 1.0.0"
    "ik: closed form d0 = 12.500000 mm in 0 iterations"
    "autograsp: d0 = (19\\.[89]|20\\.[0-2])[0-9]* mm"
    "quality force_closure = 1 from plugin gripper3 1.0.0"
    "all checks passed")
  if(NOT out MATCHES "${expected}")
    message(FATAL_ERROR "load_custom_robot output lacks '${expected}':\n${out}")
  endif()
endforeach()
message(STATUS "${out}")
