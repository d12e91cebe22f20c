# `graspkit info --json` on the project's bh8 hand: the fingertip frames at all DOFs 0 must sit
# where the DH parameters put them by hand: radial 50 + 70 cos 5deg + 50 cos 45deg = 155.088968,
# height 70 sin 5deg + 50 sin 45deg = 41.456241 (models/README.md).
execute_process(COMMAND ${GRASPKIT} info ${SOURCE_DIR}/models/robots/bh8/bh8.xml --dofs 0,0,0,0 --json
                OUTPUT_VARIABLE out RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "graspkit info failed (${rc})")
endif()

function(expect_near actual expected what)
  # CMake has no floating-point arithmetic; awk does the comparison.
  execute_process(COMMAND awk "BEGIN { d = (${actual}) - (${expected}); if (d < 0) d = -d; exit (d > 1e-5) }"
                  RESULT_VARIABLE far)
  if(far)
    message(FATAL_ERROR "${what}: ${actual}, expected ${expected}")
  endif()
endfunction()

string(JSON robots LENGTH "${out}" robots)
if(NOT robots EQUAL 1)
  message(FATAL_ERROR "expected one robot, got ${robots}")
endif()
string(JSON name GET "${out}" robots 0 name)
if(NOT name STREQUAL "bh8")
  message(FATAL_ERROR "robot name ${name}")
endif()
# chain, expected x, expected y
foreach(case "0;25;155.088968" "1;-25;155.088968" "2;0;-155.088968")
  list(GET case 0 chain)
  list(GET case 1 x)
  list(GET case 2 y)
  string(JSON links LENGTH "${out}" robots 0 chains ${chain} links)
  math(EXPR last "${links} - 1")
  string(JSON tx GET "${out}" robots 0 chains ${chain} links ${last} translation 0)
  string(JSON ty GET "${out}" robots 0 chains ${chain} links ${last} translation 1)
  string(JSON tz GET "${out}" robots 0 chains ${chain} links ${last} translation 2)
  expect_near("${tx}" "${x}" "chain ${chain} tip x")
  expect_near("${ty}" "${y}" "chain ${chain} tip y")
  expect_near("${tz}" "41.456241" "chain ${chain} tip z")
endforeach()
