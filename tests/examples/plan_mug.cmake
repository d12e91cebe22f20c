# examples/plan_mug.lua plans grasps of the default world's mug (3000 steps, seed 1, top 5).
# Checked against: `graspkit plan --json` with the same budget and seed and nothing else given
# (the defaults are the host layer's in both, so the steps, energies and palm positions must
# match rank for rank), the best list's order (force closure first, then the larger epsilon),
# and the meaning of force closure (yes exactly when epsilon > 0).
include(${CMAKE_CURRENT_LIST_DIR}/example_support.cmake)

run_example(out run plan_mug.lua)
expect_output("${out}" "\n5 grasps, [0-5] force closure\n" "five grasps")

execute_process(COMMAND ${GRASPKIT} -q plan models/worlds/default.xml --root models
                        --steps 3000 --top 5 --seed 1 --json
                WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE json ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "graspkit plan failed (${rc}): ${err}")
endif()

string(JSON cli_steps GET "${json}" steps)
expect_output("${out}" "^${cli_steps} steps in" "the steps graspkit plan took")
if(cli_steps LESS 3000)
  message(FATAL_ERROR "graspkit plan took ${cli_steps} steps of a 3000-step budget")
endif()

set(rank 0)
set(previous "")
set(previous_fc "yes")
string(REGEX MATCHALL "\n +[1-5] +[-0-9.]+ +[-0-9.]+ +[-0-9.]+ +[0-9]+ +(yes|no)  [^\n]+" rows "${out}")
list(LENGTH rows count)
if(NOT count EQUAL 5)
  message(FATAL_ERROR "expected 5 grasp rows, found ${count}:\n${out}")
endif()
foreach(row ${rows})
  string(REGEX MATCH " +([1-5]) +([-0-9.]+) +([-0-9.]+) +([-0-9.]+) +([0-9]+) +(yes|no)  ([-0-9.]+) ([-0-9.]+) ([-0-9.]+)" _ "${row}")
  set(energy ${CMAKE_MATCH_2})
  set(epsilon ${CMAKE_MATCH_3})
  set(fc ${CMAKE_MATCH_6})
  set(palm ${CMAKE_MATCH_7} ${CMAKE_MATCH_8} ${CMAKE_MATCH_9})
  if((fc STREQUAL "yes") AND NOT epsilon GREATER 0 OR (fc STREQUAL "no") AND epsilon GREATER 0)
    message(FATAL_ERROR "force closure '${fc}' with epsilon ${epsilon}: ${row}")
  endif()
  if(fc STREQUAL "yes" AND previous_fc STREQUAL "no")
    message(FATAL_ERROR "a force-closure grasp ranks after one without: ${row}")
  endif()
  if(fc STREQUAL previous_fc AND fc STREQUAL "yes" AND NOT previous STREQUAL ""
     AND epsilon GREATER previous)
    message(FATAL_ERROR "epsilons out of order: ${previous} then ${epsilon}")
  endif()
  set(previous ${epsilon})
  set(previous_fc ${fc})
  string(JSON cli_energy GET "${json}" grasps ${rank} energy)
  expect_close("${energy}" "${cli_energy}" 0.0001 "rank ${rank} energy (Lua and graspkit plan)")
  foreach(axis 0 1 2)
    list(GET palm ${axis} lua_value)
    string(JSON cli_value GET "${json}" grasps ${rank} translation ${axis})
    expect_close("${lua_value}" "${cli_value}" 0.06 "rank ${rank} palm coordinate ${axis}")
  endforeach()
  math(EXPR rank "${rank} + 1")
endforeach()
