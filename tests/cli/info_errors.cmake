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
