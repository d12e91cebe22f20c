# `graspkit grasp --autograsp --json` on GraspIt!'s plannerMug reproduces GraspIt!'s own figures
# (../shared/reference/graspit-figures.json): 6 contacts and no force closure as loaded; 4
# contacts, force closure and epsilon 0.0027506 from the recorded pose and DOFs.
if(NOT EXISTS ${SHARED_DIR}/graspit-data/worlds/plannerMug.xml)
  message(WARNING "SKIPPED: ${SHARED_DIR}/graspit-data is absent")
  return()
endif()
set(world ${SHARED_DIR}/graspit-data/worlds/plannerMug.xml)

execute_process(COMMAND ${GRASPKIT} -q grasp ${world} --autograsp --json
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "grasp failed (${rc}): ${err}")
endif()
string(JSON count LENGTH "${out}" contacts)
string(JSON closure GET "${out}" force_closure)
string(JSON eps GET "${out}" epsilon)
string(JSON link GET "${out}" contacts 0 link)
string(JSON mu GET "${out}" contacts 0 mu)
if(NOT count EQUAL 6 OR closure OR NOT eps EQUAL -1 OR NOT link MATCHES "^Barrett_chain"
   OR NOT mu EQUAL 0.3)
  message(FATAL_ERROR "as loaded: ${count} contacts, closure ${closure}, eps ${eps}, ${link} mu ${mu}")
endif()

execute_process(COMMAND ${GRASPKIT} -q grasp ${world} --autograsp --json
  --pose 43.5961787202,-51.0196446134,190.547088948,0.230240016789,-0.849067984447,-0.365073354129,0.304621960077
  --dofs 1.59401061648,0.737072671249,0.737072671249,0.737072671249
  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "grasp failed (${rc}): ${err}")
endif()
string(JSON count LENGTH "${out}" contacts)
string(JSON closure GET "${out}" force_closure)
string(JSON eps GET "${out}" epsilon)
string(JSON dof2 GET "${out}" dof_values 2)
if(NOT count EQUAL 4 OR NOT closure OR eps LESS 0.002723 OR eps GREATER 0.002778
   OR dof2 LESS 1.4101 OR dof2 GREATER 1.4103)
  message(FATAL_ERROR "force_closure_1: ${count} contacts, closure ${closure}, eps ${eps}, dof2 ${dof2}")
endif()

# With no --robot, the hand is the world's first robot that is a hand (GraspIt!'s current hand):
# in barrettGlassDyn the Puma arm comes first and the Barrett closes on the glass, 4 contacts and
# volume 0.000229 in GraspIt! (graspkit's contacts give 0.0002276, within 1%).
execute_process(COMMAND ${GRASPKIT} -q grasp ${SHARED_DIR}/graspit-data/worlds/barrettGlassDyn.xml
                        --autograsp --json
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "barrettGlassDyn grasp failed (${rc}): ${err}")
endif()
string(JSON hand GET "${out}" robot)
string(JSON count LENGTH "${out}" contacts)
string(JSON volume GET "${out}" volume)
if(NOT hand STREQUAL "Barrett" OR NOT count EQUAL 4 OR volume LESS 0.0002267 OR
   volume GREATER 0.0002313)
  message(FATAL_ERROR "barrettGlassDyn: hand ${hand}, ${count} contacts, volume ${volume}")
endif()

# Contacts with the object and the hand's others apart: Robonaut closing in robonautFlask touches
# the flask nowhere and itself 6 times (3 finger pairs, each from both sides), as in GraspIt!.
execute_process(COMMAND ${GRASPKIT} -q grasp ${SHARED_DIR}/graspit-data/worlds/robonautFlask.xml
                        --autograsp --json
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "robonautFlask grasp failed (${rc}): ${err}")
endif()
string(JSON count LENGTH "${out}" contacts)
string(JSON others LENGTH "${out}" other_contacts)
if(NOT count EQUAL 0 OR NOT others EQUAL 6)
  message(FATAL_ERROR "robonautFlask: ${count} object contacts, ${others} others")
endif()
math(EXPR last "${others} - 1")
foreach(i RANGE ${last})
  string(JSON kind GET "${out}" other_contacts ${i} kind)
  if(NOT kind STREQUAL "self")
    message(FATAL_ERROR "robonautFlask: other contact ${i} is '${kind}', not 'self'")
  endif()
endforeach()

# The report says how the autograsp ended: GraspIt!'s plannerMug closes until every finger has
# stopped on the mug ("settled"), and as loaded the hand touches nothing it intersects.
execute_process(COMMAND ${GRASPKIT} -q grasp ${world} --autograsp --json
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
string(JSON ended GET "${out}" autograsp ended)
string(JSON steps GET "${out}" autograsp steps)
string(JSON start LENGTH "${out}" start_collisions)
if(NOT ended STREQUAL "settled" OR steps LESS 1 OR NOT start EQUAL 0)
  message(FATAL_ERROR "as loaded: autograsp ended '${ended}' after ${steps} steps, "
                      "${start} start collisions")
endif()

# A hand placed through the mug (palm at the mug's centre, 105.8 mm up) intersects it: a
# warning on stderr and the pairs in the JSON, instead of a silent "0 contacts".
execute_process(COMMAND ${GRASPKIT} grasp ${world} --json --pose 0,0.78,105.8,1,0,0,0
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "grasp with the hand in the mug failed (${rc}): ${err}")
endif()
string(JSON start LENGTH "${out}" start_collisions)
string(JSON body GET "${out}" start_collisions 0 body)
if(start LESS 1 OR NOT body STREQUAL "mug" OR NOT err MATCHES "starts in collision")
  message(FATAL_ERROR "hand in the mug: ${start} start collisions (first with '${body}'), "
                      "stderr: ${err}")
endif()
