# examples/mug_grasp_test.lua under `graspkit test` (needs the test command): every test passes;
# and a copy with one wrong expectation (the mug's radius 41 mm instead of 40) fails with exit
# status 1 naming that expectation, so the file's checks do run.
include(${CMAKE_CURRENT_LIST_DIR}/example_support.cmake)

run_example(out test mug_grasp_test.lua)

fresh_work_dir(${WORK_DIR}/mutant)
file(READ ${SOURCE_DIR}/examples/mug_grasp_test.lua source)
string(REPLACE "local MUG_RADIUS, MUG_HEIGHT, MUG_Z = 40, 100, 50"
               "local MUG_RADIUS, MUG_HEIGHT, MUG_Z = 41, 100, 50" mutant "${source}")
string(REPLACE "graspkit.script_folder .. \"/../models/worlds/default.xml\""
               "\"${SOURCE_DIR}/models/worlds/default.xml\"" mutant "${mutant}")
if(mutant STREQUAL source)
  message(FATAL_ERROR "the mutation did not apply: update this test with the example")
endif()
file(WRITE ${WORK_DIR}/mutant/mug_mutant_test.lua "${mutant}")
execute_process(COMMAND ${GRASPKIT} -q test ${WORK_DIR}/mutant/mug_mutant_test.lua --root models
                WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 1 OR NOT "${out}${err}" MATCHES "expect_near")
  message(FATAL_ERROR "the mutant should fail an expect_near with exit status 1; got ${rc}:\n${out}\n${err}")
endif()
