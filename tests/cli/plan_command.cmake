# `graspkit plan` on GraspIt!'s plannerMug, run as a user would: the JSON it prints, the same
# grasps for the same seed, the files --out writes (each saved world loaded again by `graspkit
# grasp`, which must find the closed DOFs the plan reports), and bad input refused with a
# message and a non-zero exit.
if(NOT EXISTS ${SHARED_DIR}/graspit-data/worlds/plannerMug.xml)
  message(WARNING "SKIPPED: ${SHARED_DIR}/graspit-data is absent")
  return()
endif()
set(data ${SHARED_DIR}/graspit-data)
set(world ${data}/worlds/plannerMug.xml)
set(work ${WORK_DIR}/plan_command)
file(REMOVE_RECURSE ${work})
file(MAKE_DIRECTORY ${work})
# Small: a few seconds on one core.
set(plan_args plan ${world} --json --steps 1500 --threads 1 --seed 3 --top 6)

function(run_plan out_var)
  execute_process(COMMAND ${GRASPKIT} -q ${plan_args} ${ARGN}
                  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "plan ${ARGN} failed (${rc}): ${err}")
  endif()
  set(${out_var} "${out}" PARENT_SCOPE)
endfunction()

run_plan(first)

# The run's figures.
foreach(key steps seconds seed threads grasps)
  string(JSON type ERROR_VARIABLE missing TYPE "${first}" ${key})
  if(missing)
    message(FATAL_ERROR "the plan JSON has no '${key}': ${first}")
  endif()
endforeach()
string(JSON steps GET "${first}" steps)
string(JSON seed GET "${first}" seed)
string(JSON threads GET "${first}" threads)
if(steps LESS 1500 OR NOT seed EQUAL 3 OR NOT threads EQUAL 1)
  message(FATAL_ERROR "steps ${steps}, seed ${seed}, threads ${threads}")
endif()

# Each grasp: a pose (3 + unit quaternion), 4 Barrett DOFs, and its measures.
string(JSON count LENGTH "${first}" grasps)
if(count LESS 1 OR count GREATER 6)
  message(FATAL_ERROR "expected 1..6 grasps (--top 6), got ${count}")
endif()
math(EXPR last "${count} - 1")
foreach(i RANGE ${last})
  foreach(key energy epsilon volume contacts)
    string(JSON type ERROR_VARIABLE missing TYPE "${first}" grasps ${i} ${key})
    if(missing OR NOT type STREQUAL "NUMBER")
      message(FATAL_ERROR "grasp ${i}: '${key}' is not a number (${type})")
    endif()
  endforeach()
  string(JSON n LENGTH "${first}" grasps ${i} translation)
  string(JSON m LENGTH "${first}" grasps ${i} quaternion)
  string(JSON d LENGTH "${first}" grasps ${i} dofs)
  if(NOT n EQUAL 3 OR NOT m EQUAL 4 OR NOT d EQUAL 4)
    message(FATAL_ERROR "grasp ${i}: translation ${n}, quaternion ${m}, dofs ${d} values")
  endif()
endforeach()

# The same seed gives the same grasps (the JSON minus its timing).
run_plan(second)
foreach(doc first second)
  string(JSON ${doc}_grasps GET "${${doc}}" grasps)
endforeach()
if(NOT first_grasps STREQUAL second_grasps)
  message(FATAL_ERROR "two runs with seed 3 differ:\n${first_grasps}\n---\n${second_grasps}")
endif()

# --out: the JSON (the same grasps as printed) and one world per grasp that loads again with the
# hand closed as the plan reported.
run_plan(printed --out ${work}/mug_plan.json)
file(READ ${work}/mug_plan.json saved)
string(JSON saved_grasps GET "${saved}" grasps)
if(NOT saved_grasps STREQUAL first_grasps)
  message(FATAL_ERROR "--out wrote other grasps than the run printed")
endif()
string(JSON files LENGTH "${saved}" world_files)
if(NOT files EQUAL count)
  message(FATAL_ERROR "${files} world files for ${count} grasps")
endif()
# A decimal number cut to 5 decimals, "-1" and "-1.0" alike giving "-1.00000".
function(five_decimals out value)
  if(NOT value MATCHES "\\.")
    set(value "${value}.")
  endif()
  string(REGEX REPLACE "^(-?[0-9]+\\.[0-9]*).*" "\\100000" value "${value}")
  string(REGEX REPLACE "^(-?[0-9]+\\.[0-9][0-9][0-9][0-9][0-9]).*" "\\1" value "${value}")
  set(${out} "${value}" PARENT_SCOPE)
endfunction()
# Loads each world a plan saved (`saved`: its JSON) with `graspkit grasp` and appends to
# `mismatches` whatever differs from the plan: contacts, epsilon, closed DOFs.
set(mismatches "")
function(check_reload saved)
  string(JSON files LENGTH "${saved}" world_files)
  math(EXPR last "${files} - 1")
  foreach(i RANGE ${last})
    string(JSON file GET "${saved}" world_files ${i})
    # Named relative to the plan's folder (both plans are written in ${work}).
    if(IS_ABSOLUTE "${file}")
      message(FATAL_ERROR "world file ${file} is not named relative to the plan")
    endif()
    set(file ${work}/${file})
    if(NOT EXISTS ${file})
      message(FATAL_ERROR "world file ${file} was not written")
    endif()
    string(JSON planned GET "${saved}" grasps ${i} epsilon)
    # Saved worlds name GraspIt!'s models so that they load without its root.
    execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=GRASPKIT_ROOT --unset=GRASPIT
                            ${GRASPKIT} -q grasp ${file} --json
                    OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "the saved world ${file} does not load (${rc}): ${err}")
    endif()
    # The saved world must hold the closed hand the plan measured: its DOFs, to 5 decimals, and,
    # measured again from the file, the same contacts and epsilon (breakaway state included).
    foreach(key contacts epsilon)
      string(JSON planned_value GET "${saved}" grasps ${i} ${key})
      string(JSON reloaded_value GET "${out}" ${key})
      if(key STREQUAL "contacts")
        string(JSON reloaded_value LENGTH "${out}" contacts)
      endif()
      five_decimals(p5 "${planned_value}")
      five_decimals(m5 "${reloaded_value}")
      if(NOT p5 STREQUAL m5)
        string(APPEND mismatches "  grasp ${i} (${file}): ${key} planned ${planned_value}, "
                                 "reloaded ${reloaded_value}\n")
      endif()
    endforeach()
    string(JSON ndofs LENGTH "${saved}" grasps ${i} closed_dofs)
    math(EXPR lastdof "${ndofs} - 1")
    foreach(k RANGE ${lastdof})
      string(JSON planned GET "${saved}" grasps ${i} closed_dofs ${k})
      string(JSON measured GET "${out}" dof_values ${k})
      five_decimals(p5 "${planned}")
      five_decimals(m5 "${measured}")
      if(NOT p5 STREQUAL m5)
        string(APPEND mismatches "  grasp ${i} (${file}): DOF ${k} planned ${planned}, "
                                 "saved ${measured}\n")
      endif()
    endforeach()
  endforeach()
  set(mismatches "${mismatches}" PARENT_SCOPE)
endfunction()
check_reload("${saved}")

# A hand whose close moves its base (the 2010 PR2 gripper), with the compliant-wrist close that
# moves an off-centre grasp: its saved worlds reload as planned too.
file(WRITE ${work}/pr2_cube.xml "<?xml version=\"1.0\" ?>
<world>
  <graspableBody><filename>models/objects/cube.xml</filename>
    <transform><fullTransform>(+1 0 0 0)[0 0 0]</fullTransform></transform></graspableBody>
  <robot><filename>models/robots/pr2_gripper/pr2_gripper_2010.xml</filename>
    <transform><fullTransform>(+1 0 0 0)[0 0 300]</fullTransform></transform></robot>
</world>
")
execute_process(COMMAND ${GRASPKIT} -q plan ${work}/pr2_cube.xml --root ${data} --steps 3000
                        --threads 1 --top 5 --out ${work}/pr2_plan.json
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "plan on the PR2 gripper failed (${rc}): ${err}")
endif()
file(READ ${work}/pr2_plan.json pr2_saved)
check_reload("${pr2_saved}")

# Bad input: a non-zero exit and a message that names the problem, never a crash.
function(expect_error pattern)
  execute_process(COMMAND ${GRASPKIT} -q plan ${ARGN} OUTPUT_VARIABLE out ERROR_VARIABLE err
                  RESULT_VARIABLE rc)
  if(rc EQUAL 0 OR NOT rc MATCHES "^[0-9]+$" OR rc GREATER 127 OR NOT err MATCHES "${pattern}")
    message(FATAL_ERROR "plan ${ARGN}: expected an error matching '${pattern}', got ${rc}: ${err}")
  endif()
endfunction()
set(small ${world} --steps 10 --threads 1)
expect_error("planner 'nope'" ${small} --planner nope)
expect_error("search energy 'nope'" ${small} --energy nope)
expect_error("--threads: Value 0 not in range 1 to 4096" ${world} --steps 10 --threads 0)
expect_error("--seconds excludes --steps|--steps excludes --seconds" ${world} --steps 10 --seconds 1)
expect_error("no-such-world.xml" ${data}/worlds/no-such-world.xml --steps 10)
expect_error("unknown position space 'bogus'" ${small} --space bogus)
expect_error("unknown posture space 'bogus'" ${small} --posture bogus)
expect_error("unknown preset 'FAST'" ${small} --preset FAST)
expect_error("--set: 'x' is not KEY=VALUE" ${small} --set x)
expect_error("unknown option 'bogus'" ${small} --set bogus=1)
# --out is checked before planning: a folder, or a file in a folder that does not exist.
expect_error("is a folder" ${small} --out ${work})
expect_error("does not exist" ${small} --out ${work}/no/such/plan.json)
if(EXISTS ${work}/no)
  message(FATAL_ERROR "a refused --out left files behind")
endif()

# Last, so that every other check has run.
if(mismatches)
  message(FATAL_ERROR "saved worlds do not reproduce the planned grasps:\n${mismatches}")
endif()

# A seed is a whole number from 0 to 2^64 - 1: -1 and 2^64 are usage errors (CLI11 would make
# both 2^64 - 1, so two different seeds would give the same run), 2^64 - 1 itself is a seed.
foreach(bad -1 18446744073709551616 1e3)
  execute_process(COMMAND ${GRASPKIT} -q plan ${SHARED_DIR}/graspit-data/worlds/plannerMug.xml
                          --steps 10 --seed ${bad}
                  OUTPUT_QUIET ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 2 OR NOT err MATCHES "is not a seed")
    message(FATAL_ERROR "plan --seed ${bad}: exit ${rc}: ${err}")
  endif()
endforeach()
