# `graspkit plugins` lists the project's robot plugins with no configuration, reports broken
# plugins on GRASPKIT_PLUGIN_PATH with their reasons (exit 1), and a robot of an unknown type
# fails to load unless --generic-robots asks for the fallback.

execute_process(COMMAND ${GRASPKIT} plugins --json OUTPUT_VARIABLE out ERROR_VARIABLE err
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "graspkit plugins failed (${rc}): ${err}\n${out}")
endif()
# Every special robot type GraspIt! has comes from one of our plugins.
foreach(type Barrett Puma560 Robonaut Shadow Pr2Gripper Pr2Gripper2010 RobotIQ HumanHand McGrip
             M7 M7Tool)
  string(JSON count LENGTH "${out}" plugins)
  set(found FALSE)
  math(EXPR last "${count} - 1")
  foreach(i RANGE ${last})
    string(JSON types GET "${out}" plugins ${i} provides robot_types)
    if(types MATCHES "\"${type}\"")
      set(found TRUE)
    endif()
  endforeach()
  if(NOT found)
    message(FATAL_ERROR "no plugin provides robot type ${type}:\n${out}")
  endif()
endforeach()
string(JSON builtin GET "${out}" builtin robot_types)
if(NOT builtin MATCHES "\"Hand\"" OR NOT builtin MATCHES "\"Robot\"")
  message(FATAL_ERROR "built-in robot types missing: ${builtin}")
endif()

# Broken plugins on the path: listed with their reasons, exit 1, no crash.
set(ENV{GRASPKIT_PLUGIN_PATH} "${PLUGIN_CORPUS}/broken")
execute_process(COMMAND ${GRASPKIT} plugins OUTPUT_VARIABLE out ERROR_VARIABLE err
                RESULT_VARIABLE rc)
unset(ENV{GRASPKIT_PLUGIN_PATH})
if(NOT rc EQUAL 1)
  message(FATAL_ERROR "broken plugins on the path, exit ${rc} (want 1): ${err}\n${out}")
endif()
foreach(expected "FAILED ${PLUGIN_CORPUS}/broken/throws.so: plugin 'throws' threw while registering"
                 "FAILED ${PLUGIN_CORPUS}/broken/wrong_abi.so: built for plugin ABI 999"
                 "barrett 1.0.0")
  string(FIND "${out}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "missing '${expected}' in:\n${out}")
  endif()
endforeach()

# A robot whose type no plugin provides.
set(dir ${WORK_DIR}/unknown_type)
file(REMOVE_RECURSE ${dir})
file(COPY ${SOURCE_DIR}/models/robots/parallel_jaw DESTINATION ${dir})
file(READ ${dir}/parallel_jaw/parallel_jaw.xml xml)
string(REPLACE "type=\"Hand\"" "type=\"WarpDriveGripper\"" xml "${xml}")
file(WRITE ${dir}/parallel_jaw/parallel_jaw.xml "${xml}")

execute_process(COMMAND ${GRASPKIT} info ${dir}/parallel_jaw/parallel_jaw.xml
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(rc EQUAL 0)
  message(FATAL_ERROR "a robot of unknown type loaded:\n${out}")
endif()
foreach(expected "parallel_jaw.xml:" "<robot>" "unknown robot type 'WarpDriveGripper'"
                 "available: " "Barrett" "plugin search path: ")
  string(FIND "${err}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "missing '${expected}' in: ${err}")
  endif()
endforeach()

execute_process(COMMAND ${GRASPKIT} info --generic-robots ${dir}/parallel_jaw/parallel_jaw.xml
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "--generic-robots did not load the robot (${rc}): ${err}")
endif()
if(NOT err MATCHES "no plugin provides robot type 'WarpDriveGripper'; loaded as a generic Hand")
  message(FATAL_ERROR "the fallback was not announced: ${err}")
endif()

# Each kind of name is listed under its own key: the simann plugin provides the planner
# "simann" (never a quality measure), and the engine's own search energies are built in.
execute_process(COMMAND ${GRASPKIT} plugins --json OUTPUT_VARIABLE listing RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "graspkit plugins --json failed (${rc})")
endif()
function(provided_by plugin_name kind out_var)
  string(JSON count LENGTH "${listing}" plugins)
  math(EXPR last "${count} - 1")
  set(names "")
  foreach(i RANGE ${last})
    string(JSON loaded GET "${listing}" plugins ${i} loaded)
    if(NOT loaded)
      continue()
    endif()
    string(JSON name GET "${listing}" plugins ${i} name)
    if(name STREQUAL plugin_name)
      string(JSON names GET "${listing}" plugins ${i} provides ${kind})
    endif()
  endforeach()
  set(${out_var} "${names}" PARENT_SCOPE)
endfunction()
provided_by(simann planners simann_planners)
provided_by(simann quality_measures simann_measures)
if(NOT simann_planners MATCHES "\"simann\"" OR simann_measures MATCHES "simann")
  message(FATAL_ERROR "simann's planner is listed as '${simann_planners}' (planners), "
                      "'${simann_measures}' (quality measures)")
endif()
string(JSON builtin_energies GET "${listing}" builtin search_energies)
if(NOT builtin_energies MATCHES "\"contact\"" OR NOT builtin_energies MATCHES "\"autograsp-quality\"")
  message(FATAL_ERROR "built-in search energies missing: ${builtin_energies}")
endif()
