# examples/autograsp_mug.lua closes the bh8 on the mug of the default world. Checked against
# the facts the result must respect: the three fingers each touch the mug, every contact closer
# than GraspIt!'s 0.2 mm threshold with mu 1.0 (rubber fingers on glass, GraspIt!'s friction
# table), the flexion DOFs past their start (0.2) and short of their limit (2.4435), force
# closure with epsilon > 0; and the same grasp as `graspkit grasp --autograsp --json` reports.
include(${CMAKE_CURRENT_LIST_DIR}/example_support.cmake)

run_example(out run autograsp_mug.lua)
expect_output("${out}" "hand: bh8 \\(Hand, 4 DOFs\\), object: mug" "the hand and the object")
expect_output("${out}" "contacts: 3\n" "3 contacts")
foreach(finger chain0_link2 chain1_link2 chain2_link1)
  expect_output("${out}" "bh8_${finger} +at [^\n]*gap 0\\.[01][0-9][0-9] mm  mu 1\\.00\n"
                "a contact of bh8_${finger} within 0.2 mm, mu 1.0")
endforeach()
expect_output("${out}" "force closure: yes" "force closure")

string(REGEX MATCH "DOFs after: +([0-9.]+) ([0-9.]+) ([0-9.]+) ([0-9.]+)" dofs "${out}")
foreach(i 2 3 4)
  if(NOT CMAKE_MATCH_${i} GREATER 0.2 OR NOT CMAKE_MATCH_${i} LESS 2.4435)
    message(FATAL_ERROR "flexion DOF ${i} ended at ${CMAKE_MATCH_${i}}: ${dofs}")
  endif()
endforeach()
string(REGEX MATCH "epsilon: ([0-9.-]+)" _ "${out}")
set(epsilon ${CMAKE_MATCH_1})
string(REGEX MATCH "volume: ([0-9.-]+)" _ "${out}")
set(volume ${CMAKE_MATCH_1})
if(NOT epsilon GREATER 0 OR NOT volume GREATER 0)
  message(FATAL_ERROR "epsilon ${epsilon}, volume ${volume}: a force-closure grasp has both > 0")
endif()

# The command line closes the same hand through the C++ API directly.
execute_process(COMMAND ${GRASPKIT} -q grasp models/worlds/default.xml --autograsp --json
                WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE json ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "graspkit grasp failed (${rc}): ${err}")
endif()
string(JSON cli_count LENGTH "${json}" contacts)
string(JSON cli_closure GET "${json}" force_closure)
string(JSON cli_epsilon GET "${json}" epsilon)
if(NOT cli_count EQUAL 3 OR NOT cli_closure)
  message(FATAL_ERROR "graspkit grasp: ${cli_count} contacts, force closure ${cli_closure}")
endif()
expect_close("${epsilon}" "${cli_epsilon}" 0.000001 "epsilon from Lua and from graspkit grasp")
