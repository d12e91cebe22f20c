# simulate and validate run as a user would: the project's box dropped on its floor comes to
# rest 0.1 mm above it (box.xml is 120 mm tall, floor.xml's top is z = 0); the world simulate
# saves loads back and stays put; the trajectory has one line per --every steps; gravity off
# keeps the box where it is; bad input is refused with a message; validate labels a grasp of a
# plan in 6 directions.
set(work ${WORK_DIR}/dynamics)
file(REMOVE_RECURSE ${work})
file(MAKE_DIRECTORY ${work})
set(models ${SOURCE_DIR}/models)

function(write_drop_world file z)
  file(WRITE ${file} "<?xml version=\"1.0\" ?>
<world>
  <obstacle>
    <filename>obstacles/floor.xml</filename>
    <transform><fullTransform>(+1 0 0 0)[0 0 0]</fullTransform></transform>
  </obstacle>
  <graspableBody>
    <filename>objects/box.xml</filename>
    <transform><fullTransform>(+1 0 0 0)[0 0 ${z}]</fullTransform></transform>
  </graspableBody>
</world>
")
endfunction()

# graspkit_json(VAR args...): runs graspkit, which must exit 0, and returns its stdout.
function(graspkit_json var)
  execute_process(COMMAND ${GRASPKIT} -q ${ARGN} WORKING_DIRECTORY ${work}
                  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "graspkit ${ARGN} failed (${rc}): ${out}${err}")
  endif()
  set(${var} "${out}" PARENT_SCOPE)
endfunction()

function(graspkit_fails status text)
  execute_process(COMMAND ${GRASPKIT} ${ARGN} WORKING_DIRECTORY ${work}
                  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL status)
    message(FATAL_ERROR "graspkit ${ARGN}: exit ${rc}, expected ${status}: ${out}${err}")
  endif()
  string(FIND "${out}${err}" "${text}" at)
  if(at LESS 0)
    message(FATAL_ERROR "graspkit ${ARGN}: expected '${text}' in: ${out}${err}")
  endif()
endfunction()

# The box's z in a simulate --json report.
function(box_z report var)
  string(JSON z GET "${report}" bodies 1 position 2)
  set(${var} ${z} PARENT_SCOPE)
endfunction()

write_drop_world(${work}/drop.xml 100)
graspkit_json(report simulate drop.xml --root ${models} --seconds 1 --json --out rest.xml
              --trajectory drop.jsonl --every 100)
string(JSON completed GET "${report}" completed)
if(NOT completed)
  message(FATAL_ERROR "simulate did not complete: ${report}")
endif()
box_z("${report}" z)
# Resting: the box's centre 60 mm (half its height) + 0.1 mm above the floor.
if(z LESS 60.05 OR z GREATER 60.15)
  message(FATAL_ERROR "the box rests at z = ${z}, expected 60.1 +- 0.05")
endif()
file(STRINGS ${work}/drop.jsonl lines)
list(LENGTH lines count)
if(NOT count EQUAL 5)  # the start, then every 100 of 400 steps
  message(FATAL_ERROR "drop.jsonl has ${count} lines, expected 5")
endif()

# The saved world loads back with the box where it was, and it stays there.
graspkit_json(again simulate rest.xml --root ${models} --seconds 0.5 --json)
box_z("${again}" z2)
if(z2 LESS 60.05 OR z2 GREATER 60.15)
  message(FATAL_ERROR "the reloaded box moved from ${z} to ${z2}")
endif()

# GraspIt!'s world without gravity: the box hangs where it was put.
graspkit_json(still simulate drop.xml --root ${models} --seconds 0.5 --gravity off --json)
box_z("${still}" z3)
if(NOT z3 EQUAL 100)
  message(FATAL_ERROR "without gravity the box moved to z = ${z3}")
endif()

graspkit_fails(1 "time step" simulate drop.xml --root ${models} --dt 0)
graspkit_fails(1 "time step" simulate drop.xml --root ${models} --dt 1)
graspkit_fails(1 "--gravity" simulate drop.xml --root ${models} --gravity 1,2)
graspkit_fails(1 "--gravity" simulate drop.xml --root ${models} --gravity nan,0,0)
write_drop_world(${work}/sunk.xml 30)
graspkit_fails(1 "interpenetrate" simulate sunk.xml --root ${models} --json)
graspkit_fails(1 "no hand" validate drop.xml --root ${models})

if(NOT EXISTS ${SHARED_DIR}/graspit-data/worlds/plannerMug.xml)
  message(WARNING "SKIPPED: ${SHARED_DIR}/graspit-data is absent")
  return()
endif()
graspkit_json(plan plan ${SHARED_DIR}/graspit-data/worlds/plannerMug.xml --steps 1500 --threads 1
              --seed 3 --top 2 --out ${work}/plan.json)
graspkit_json(labels validate plan.json --grasp 1 --seconds 0.1 --json)
string(JSON grasps LENGTH "${labels}" grasps)
string(JSON directions LENGTH "${labels}" grasps 0 directions)
if(NOT grasps EQUAL 1 OR NOT directions EQUAL 6)
  message(FATAL_ERROR "validate --grasp 1: ${grasps} grasps, ${directions} directions: ${labels}")
endif()

# plan --validate labels each grasp; validate on the saved plan (its world files) gives the same
# labels: the saved grasp worlds reload to the grasps the plan validated.
graspkit_json(labelled plan ${SHARED_DIR}/graspit-data/worlds/plannerMug.xml --steps 1500
              --threads 1 --seed 3 --top 2 --validate --validate-seconds 0.2
              --out ${work}/labelled.json --json)
graspkit_json(relabelled validate labelled.json --seconds 0.2 --json)
foreach(i RANGE 1)
  string(JSON planned GET "${labelled}" grasps ${i} validation directions_held)
  string(JSON again GET "${relabelled}" grasps ${i} directions_held)
  if(NOT planned EQUAL again)
    message(FATAL_ERROR "grasp ${i}: plan --validate held ${planned} directions, validate ${again}")
  endif()
  foreach(k RANGE 5)
    string(JSON h1 GET "${labelled}" grasps ${i} validation directions ${k} held)
    string(JSON h2 GET "${relabelled}" grasps ${i} directions ${k} held)
    if(NOT h1 STREQUAL h2)
      message(FATAL_ERROR "grasp ${i} direction ${k}: plan --validate says ${h1}, validate ${h2}")
    endif()
  endforeach()
endforeach()
