# Shared by the examples.* tests: runs an example the way the README and docs/lua.md show it,
# from the repository root with the project's models as the model root.
#
# run_example(<out-var> <command> <script> [FLAGS flag...] [ARGS arg...])
#   Runs `graspkit -q <command> examples/<script> --root models <flags> [-- <args>]` and
#   stores its standard output in <out-var>. A non-zero exit status fails the test, showing
#   both output streams.
function(run_example out_var command script)
  cmake_parse_arguments(PARSE_ARGV 3 RUN "" "" "FLAGS;ARGS")
  set(cmd ${GRASPKIT} -q ${command} examples/${script} --root models ${RUN_FLAGS})
  if(RUN_ARGS)
    list(APPEND cmd -- ${RUN_ARGS})
  endif()
  execute_process(COMMAND ${cmd} WORKING_DIRECTORY ${SOURCE_DIR}
                  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${script} exited with ${rc}\nstdout:\n${out}\nstderr:\n${err}")
  endif()
  message(STATUS "${script}:\n${out}")
  set(${out_var} "${out}" PARENT_SCOPE)
endfunction()

# expect_output(<text> <regex> <what>): fails the test when <text> does not match <regex>.
function(expect_output text regex what)
  if(NOT text MATCHES "${regex}")
    message(FATAL_ERROR "expected ${what} (/${regex}/) in:\n${text}")
  endif()
endfunction()

# A work folder, emptied first, for an example that writes files.
function(fresh_work_dir dir)
  file(REMOVE_RECURSE ${dir})
  file(MAKE_DIRECTORY ${dir})
endfunction()

# expect_close(<a> <b> <tolerance> <what>): two decimal numbers agree within <tolerance>, all
# three rounded to 7 decimals. CMake's math is integer-only, so they become counts of 1e-7.
# A number in exponent form is accepted when it is below 1e-7 in size (it counts as 0).
function(_tenths_of_micro value out)
  if(value MATCHES "^-?[0-9.]+e-([0-9]+)$" AND CMAKE_MATCH_1 GREATER 7)
    set(${out} 0 PARENT_SCOPE)
    return()
  endif()
  if(NOT value MATCHES "^(-?)([0-9]+)\\.?([0-9]*)$")
    message(FATAL_ERROR "not a plain decimal number: '${value}'")
  endif()
  set(sign "${CMAKE_MATCH_1}")
  set(whole "${CMAKE_MATCH_2}")
  string(SUBSTRING "${CMAKE_MATCH_3}00000000" 0 8 digits)
  math(EXPR units "(${whole} * 100000000 + ${digits} + 5) / 10")
  set(${out} "${sign}${units}" PARENT_SCOPE)
endfunction()

function(expect_close a b tolerance what)
  _tenths_of_micro("${a}" ua)
  _tenths_of_micro("${b}" ub)
  _tenths_of_micro("${tolerance}" ut)
  math(EXPR diff "${ua} - (${ub})")
  if(diff GREATER ut OR diff LESS -${ut})
    message(FATAL_ERROR "${what}: ${a} and ${b} differ by more than ${tolerance}")
  endif()
endfunction()

# parse_sweep_table(<text> <count>): checks the table grasp_sweep.lua prints (angle, contacts,
# epsilon, volume, force closure) has one row per angle 360 * i / <count> degrees, in order,
# and that force closure is reported exactly when epsilon > 0 (epsilon is the radius of the
# largest ball around the origin inside the wrench space, so the two are one fact). Sets
# BEST_EPSILON and BEST_ANGLE (the first row with the largest epsilon) and CLOSURES (the rows
# with force closure) in the caller's scope.
function(parse_sweep_table text count)
  set(row_regex "\n +([0-9]+\\.[0-9]) +([0-9]+) +(-?[0-9]+\\.[0-9]+) +(-?[0-9]+\\.[0-9]+) +(yes|no)")
  string(REGEX MATCHALL "${row_regex}" rows "${text}")
  list(LENGTH rows found)
  if(NOT found EQUAL count)
    message(FATAL_ERROR "expected ${count} table rows, found ${found}:\n${text}")
  endif()
  set(best_epsilon "")
  set(closures 0)
  set(i 0)
  foreach(row IN LISTS rows)
    string(REGEX MATCH "${row_regex}" _ "${row}")
    set(angle ${CMAKE_MATCH_1})
    set(epsilon ${CMAKE_MATCH_3})
    set(closure ${CMAKE_MATCH_5})
    # 360 * i / count to one decimal, in tenths of a degree.
    math(EXPR tenths "(3600 * ${i} * 2 + ${count}) / (2 * ${count})")
    math(EXPR whole "${tenths} / 10")
    math(EXPR fraction "${tenths} % 10")
    if(NOT angle STREQUAL "${whole}.${fraction}")
      message(FATAL_ERROR "row ${i}: angle ${angle}, expected ${whole}.${fraction}")
    endif()
    if(epsilon GREATER 0 AND NOT closure STREQUAL "yes" OR
       NOT epsilon GREATER 0 AND NOT closure STREQUAL "no")
      message(FATAL_ERROR "row ${i}: epsilon ${epsilon} but force closure '${closure}'")
    endif()
    if(closure STREQUAL "yes")
      math(EXPR closures "${closures} + 1")
    endif()
    if(best_epsilon STREQUAL "" OR epsilon GREATER best_epsilon)
      set(best_epsilon ${epsilon})
      set(best_angle ${angle})
    endif()
    math(EXPR i "${i} + 1")
  endforeach()
  set(BEST_EPSILON ${best_epsilon} PARENT_SCOPE)
  set(BEST_ANGLE ${best_angle} PARENT_SCOPE)
  set(CLOSURES ${closures} PARENT_SCOPE)
endfunction()
