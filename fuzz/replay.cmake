# Replays every input kept in INPUTS through FUZZER (libFuzzer runs each file once and fails on
# any crash or sanitizer report, or on an input that takes longer than scripts/fuzz allows). An empty folder passes: nothing has failed yet.
file(GLOB inputs ${INPUTS}/*)
list(FILTER inputs EXCLUDE REGEX "README")
if(NOT inputs)
  return()
endif()
execute_process(COMMAND ${FUZZER} -timeout=20 ${inputs} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${FUZZER} fails on a kept input (${rc}):\n${out}")
endif()
