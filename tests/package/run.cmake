# Shared by the package tests: run(<what> COMMAND ...) runs a command and fails the test with
# its output on a non-zero exit; the output is left in `out` and `err`.
function(run what)  # run(<what> COMMAND ...): fails the test with the output on a non-zero exit
  execute_process(${ARGN} OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()
