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

# fresh_install_test(): an empty WORK_DIR, and an environment that cannot choose the model roots
# or the plugins (the tests of an install check that it finds its own).
macro(fresh_install_test)
  file(REMOVE_RECURSE ${WORK_DIR})
  file(MAKE_DIRECTORY ${WORK_DIR})
  unset(ENV{GRASPKIT_ROOT})
  unset(ENV{GRASPIT})
  unset(ENV{GRASPKIT_PLUGIN_PATH})
endmacro()
