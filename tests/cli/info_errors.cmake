# Bad input makes `graspkit info` exit non-zero with the file, line and element in the message,
# and a bad --dofs value is refused the same way.
execute_process(COMMAND ${GRASPKIT} info ${SOURCE_DIR}/tests/badinput/corpus/robots/malformed_unclosed.xml
                ERROR_VARIABLE err RESULT_VARIABLE rc)
if(rc EQUAL 0)
  message(FATAL_ERROR "a malformed robot file was accepted")
endif()
if(NOT err MATCHES "malformed_unclosed.xml:[0-9]+: <")
  message(FATAL_ERROR "error does not name file, line and element: ${err}")
endif()

execute_process(COMMAND ${GRASPKIT} info ${SOURCE_DIR}/models/robots/bh8/bh8.xml --dofs 0,nan,0,0
                ERROR_VARIABLE err RESULT_VARIABLE rc)
if(rc EQUAL 0 OR NOT err MATCHES "nan")
  message(FATAL_ERROR "--dofs with nan accepted (${rc}): ${err}")
endif()

execute_process(COMMAND ${GRASPKIT} info ${SOURCE_DIR}/models/robots/bh8/bh8.xml --dofs 0,0
                ERROR_VARIABLE err RESULT_VARIABLE rc)
if(rc EQUAL 0 OR NOT err MATCHES "4 DOFs, 2 values")
  message(FATAL_ERROR "--dofs with a wrong count accepted (${rc}): ${err}")
endif()

# --robot is checked without --dofs too: a wrong index must not be ignored.
execute_process(COMMAND ${GRASPKIT} info ${SOURCE_DIR}/models/worlds/gripper_box.xml --robot 99
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(rc EQUAL 0 OR NOT err MATCHES "robot 99")
  message(FATAL_ERROR "info --robot 99 accepted (${rc}): ${err}")
endif()

# Output that cannot be written (a full disk) is a failure, not exit status 0.
if(EXISTS /dev/full)
  execute_process(COMMAND ${GRASPKIT} info ${SOURCE_DIR}/models/worlds/gripper_box.xml
                  OUTPUT_FILE /dev/full ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(rc EQUAL 0 OR NOT err MATCHES "cannot write standard output")
    message(FATAL_ERROR "info writing to /dev/full exited ${rc}: ${err}")
  endif()
else()
  message(WARNING "SKIPPED the full-disk check: no /dev/full")
endif()
