# examples/save_best_grasp.lua writes the best grasp of an 8-direction sweep into a folder given
# with --allow-write. Checked from outside the script: the table's largest epsilon is the one
# saved; the file loads in `graspkit info` with the hand at the pose the script printed and in
# `graspkit grasp` with the same contacts and epsilon; the sandbox refuses a file outside the
# allowed folder and writes nothing there.
include(${CMAKE_CURRENT_LIST_DIR}/example_support.cmake)

fresh_work_dir(${WORK_DIR}/out)
set(saved ${WORK_DIR}/out/best.xml)
run_example(out run save_best_grasp.lua FLAGS --allow-write ${WORK_DIR}/out ARGS ${saved} 8)
parse_sweep_table("${out}" 8)
if(NOT EXISTS ${saved})
  message(FATAL_ERROR "${saved} was not written")
endif()
expect_output("${out}" "saved [^\n]*best\\.xml: bh8 at ${BEST_ANGLE} degrees, ([0-9]+) contacts, epsilon ${BEST_EPSILON}"
              "the best row saved")
string(REGEX MATCH "saved [^\n]*, ([0-9]+) contacts" _ "${out}")
set(contacts ${CMAKE_MATCH_1})
expect_output("${out}" "reloaded [^\n]*best\\.xml: [^\n]*${contacts} contacts, epsilon ${BEST_EPSILON}"
              "the reload check")

# The hand pose the script printed is the one `graspkit info` reads from the file.
set(number "(-?[0-9.e+-]+)")
string(REGEX MATCH "hand pose pose\\(translation = \\{${number}, ${number}, ${number}\\}, quaternion = \\{${number}, ${number}, ${number}, ${number}\\}\\)"
       pose_line "${out}")
if(NOT pose_line)
  message(FATAL_ERROR "no hand pose in:\n${out}")
endif()
set(printed ${CMAKE_MATCH_1} ${CMAKE_MATCH_2} ${CMAKE_MATCH_3} ${CMAKE_MATCH_4} ${CMAKE_MATCH_5}
            ${CMAKE_MATCH_6} ${CMAKE_MATCH_7})
execute_process(COMMAND ${GRASPKIT} -q info ${saved} --root models --json
                WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE json ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "graspkit info ${saved} failed (${rc}): ${err}")
endif()
# The script prints 6 significant digits (%g).
foreach(i 0 1 2)
  list(GET printed ${i} value)
  string(JSON loaded GET "${json}" robots 0 base translation ${i})
  expect_close("${value}" "${loaded}" 0.001 "hand translation ${i}, printed and in the file")
endforeach()

execute_process(COMMAND ${GRASPKIT} -q grasp ${saved} --root models --object mug --json
                WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE json ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "graspkit grasp ${saved} failed (${rc}): ${err}")
endif()
string(JSON cli_count LENGTH "${json}" contacts)
string(JSON cli_epsilon GET "${json}" epsilon)
if(NOT cli_count EQUAL contacts)
  message(FATAL_ERROR "graspkit grasp finds ${cli_count} contacts in ${saved}, the script ${contacts}")
endif()
# The table prints 4 decimals.
expect_close("${BEST_EPSILON}" "${cli_epsilon}" 0.00005 "epsilon of the sweep and of graspkit grasp")

# Writing outside the --allow-write folder is refused, and nothing is written.
set(outside ${WORK_DIR}/outside.xml)
file(REMOVE ${outside})
execute_process(COMMAND ${GRASPKIT} -q run examples/save_best_grasp.lua --root models
                        --allow-write ${WORK_DIR}/out -- ${outside} 1
                WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 1 OR NOT err MATCHES "sandbox: writing is not allowed" OR EXISTS ${outside})
  message(FATAL_ERROR "writing ${outside} should fail with exit status 1 and a sandbox error; "
                      "got ${rc}:\n${err}")
endif()
