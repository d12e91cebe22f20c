# examples/sweep_quality.lua: 8 directions around the mug give a table of 8 rows at 0, 45, ...,
# 315 degrees, force closure exactly where epsilon > 0, and a summary that names the largest
# epsilon of the table and counts its force-closure rows. A hand that comes at the mug from
# any side and closes its three fingers around it holds it somewhere: at least one row is force
# closure.
include(${CMAKE_CURRENT_LIST_DIR}/example_support.cmake)

run_example(out run sweep_quality.lua ARGS 8)
parse_sweep_table("${out}" 8)
if(CLOSURES LESS 1)
  message(FATAL_ERROR "no direction gave force closure:\n${out}")
endif()
expect_output("${out}"
              "force closure at ${CLOSURES} of 8 angles; best epsilon ${BEST_EPSILON} at ${BEST_ANGLE} degrees"
              "the summary of the table")
