# The command line's conventions (README, "Exit status" and "Warnings"): usage errors exit 2 with
# the program's prefix, every status is listed in --help, one kind of warning can be silenced,
# repeats are grouped, and --robot takes a 0-based index or a robot's name.
set(dir ${WORK_DIR}/conventions)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})
set(world ${SOURCE_DIR}/models/worlds/gripper_box.xml)

function(run)
  execute_process(COMMAND ${GRASPKIT} ${ARGN} OUTPUT_VARIABLE out ERROR_VARIABLE err
                  RESULT_VARIABLE rc TIMEOUT 120)
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
  set(rc "${rc}" PARENT_SCOPE)
endfunction()

function(expect_usage_error pattern)
  run(${ARGN})
  if(NOT rc EQUAL 2 OR NOT err MATCHES "^graspkit: error: " OR NOT err MATCHES "${pattern}")
    message(FATAL_ERROR "graspkit ${ARGN}: expected exit 2 and 'graspkit: error: ...${pattern}', "
                        "got ${rc}: ${err}")
  endif()
endfunction()

# Usage errors: no subcommand, an unknown option, a bad value, a missing or wrong file.
expect_usage_error("subcommand")
expect_usage_error("--frobnicate" info ${world} --frobnicate)
expect_usage_error("--top" plan ${world} --top many)
expect_usage_error("no such file: ${dir}/absent.xml" info ${dir}/absent.xml)
expect_usage_error("is a folder, not a file" grasp ${dir})
expect_usage_error("--no-warn" --no-warn nonsense info ${world})

# Bad input in a file that exists is a failure (1), not a usage error.
file(WRITE ${dir}/broken.xml "<robot><palm>\n")
run(info ${dir}/broken.xml)
if(NOT rc EQUAL 1 OR NOT err MATCHES "^graspkit: error: .*broken.xml:[0-9]+")
  message(FATAL_ERROR "info on a malformed file: expected exit 1 naming the file, got ${rc}: ${err}")
endif()

# --help lists every exit status.
run(--help)
foreach(status "0 " "1 " "2 " "3 " "124 ")
  if(NOT out MATCHES "\n  ${status}")
    message(FATAL_ERROR "--help does not document exit status ${status}:\n${out}")
  endif()
endforeach()

# Warnings: a body file with the same unknown tag on five lines warns three times, then counts the
# other two once at the end; -v shows all five; --no-warn unknown-element hides them; -q hides all.
file(WRITE ${dir}/tagged.xml
     "<?xml version=\"1.0\" ?>\n<root>\n<material>plastic</material>\n<mass>300</mass>\n"
     "<colour>1</colour>\n<colour>2</colour>\n<colour>3</colour>\n<colour>4</colour>\n"
     "<colour>5</colour>\n"
     "<geometryFile type=\"Inventor\">${SOURCE_DIR}/models/objects/box.iv</geometryFile>\n</root>\n")
function(count_warnings var)
  string(REGEX MATCHALL "tagged.xml:[0-9]+[^\n]*unknown tag" lines "${err}")
  list(LENGTH lines n)
  set(${var} ${n} PARENT_SCOPE)
endfunction()
run(info ${dir}/tagged.xml)
count_warnings(shown)
if(NOT rc EQUAL 0 OR NOT shown EQUAL 3 OR NOT err MATCHES "2 more like 'unknown tag inside <root> ignored'"
   OR NOT err MATCHES "--no-warn unknown-element")
  message(FATAL_ERROR "repeated warnings not grouped (${rc}, ${shown} shown): ${err}")
endif()
run(-v info ${dir}/tagged.xml)
count_warnings(shown)
if(NOT shown EQUAL 5 OR err MATCHES "more like")
  message(FATAL_ERROR "-v does not show every repeat (${shown} shown): ${err}")
endif()
run(info ${dir}/tagged.xml --no-warn unknown-element)
if(NOT rc EQUAL 0 OR err MATCHES "unknown tag")
  message(FATAL_ERROR "--no-warn unknown-element still warns (${rc}): ${err}")
endif()
run(--no-warn geometry info ${dir}/tagged.xml)
count_warnings(shown)
if(NOT shown EQUAL 3)
  message(FATAL_ERROR "--no-warn geometry hid another kind (${shown} shown): ${err}")
endif()
run(-q info ${dir}/tagged.xml)
if(NOT rc EQUAL 0 OR err MATCHES "warning")
  message(FATAL_ERROR "-q still warns (${rc}): ${err}")
endif()

# --robot: a 0-based index or the robot's name give the same hand; a wrong name lists the names.
run(info ${world} --json)
string(JSON robot_name GET "${out}" robots 0 name)
run(grasp ${world} --json --robot 0)
set(by_index "${out}")
run(grasp ${world} --json --robot ${robot_name})
if(NOT rc EQUAL 0 OR NOT out STREQUAL by_index)
  message(FATAL_ERROR "--robot ${robot_name} differs from --robot 0 (${rc}): ${err}\n${out}\n${by_index}")
endif()
run(grasp ${world} --robot no_such_hand)
if(NOT rc EQUAL 1 OR NOT err MATCHES "--robot 'no_such_hand': no robot of that name" OR NOT err MATCHES "${robot_name}")
  message(FATAL_ERROR "--robot no_such_hand: expected exit 1 listing the robots, got ${rc}: ${err}")
endif()
