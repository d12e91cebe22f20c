# examples/plan_mug.lua plans grasps of the default world's mug (3000 steps, seed 1, top 5).
# Checked against: the same planner run by `graspkit plan --json` through the C++ API (the
# energies and palm positions must match rank for rank), the best list's order (energies never
# decrease), and the meaning of force closure (yes exactly when epsilon > 0).
include(${CMAKE_CURRENT_LIST_DIR}/example_support.cmake)

run_example(out run plan_mug.lua)
expect_output("${out}" "^3000 steps in" "the step budget spent")
expect_output("${out}" "\n5 grasps, [0-5] force closure\n" "five grasps")

execute_process(COMMAND ${GRASPKIT} -q plan models/worlds/default.xml --root models --mode anneal
                        --threads 1 --steps 3000 --top 5 --seed 1 --json
                WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE json ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "graspkit plan failed (${rc}): ${err}")
endif()

set(rank 0)
set(previous "")
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
  if(NOT previous STREQUAL "" AND energy LESS previous)
    message(FATAL_ERROR "energies out of order: ${previous} then ${energy}")
  endif()
  set(previous ${energy})
  string(JSON cli_energy GET "${json}" grasps ${rank} energy)
  expect_close("${energy}" "${cli_energy}" 0.0001 "rank ${rank} energy (Lua and graspkit plan)")
  foreach(axis 0 1 2)
    list(GET palm ${axis} lua_value)
    string(JSON cli_value GET "${json}" grasps ${rank} translation ${axis})
    expect_close("${lua_value}" "${cli_value}" 0.06 "rank ${rank} palm coordinate ${axis}")
  endforeach()
  math(EXPR rank "${rank} + 1")
endforeach()
