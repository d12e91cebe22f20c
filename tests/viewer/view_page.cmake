# Writes the pages (a world and a plan of GraspIt!'s plannerMug, a simulation of it played back and
# its final world) and opens them in headless Chromium (view_page.cjs). Skipped loudly where the corpus, Chromium or the viewer is missing.
if(NOT EXISTS ${SHARED_DIR}/graspit-data/worlds/plannerMug.xml)
  message(WARNING "SKIPPED: ${SHARED_DIR}/graspit-data is absent")
  return()
endif()
if(NOT EXISTS "${CHROMIUM}" OR NOT EXISTS "${NODE_MODULES}/puppeteer-core")
  message(WARNING "SKIPPED: no Chromium ('${CHROMIUM}') or no viewer node_modules ('${NODE_MODULES}')")
  return()
endif()
set(world ${SHARED_DIR}/graspit-data/worlds/plannerMug.xml)
set(work ${WORK_DIR}/viewer)
file(REMOVE_RECURSE ${work})
file(MAKE_DIRECTORY ${work})
foreach(step
    "plan;${world};--steps;1500;--threads;1;--seed;3;--top;3;--out;${work}/plan.json"
    "view;${world};--html;${work}/world.html"
    "view;${work}/plan.json;--html;${work}/plan.html"
    "simulate;${world};--autograsp;--seconds;0.3;--trajectory;${work}/run.jsonl;--out;${work}/final.xml"
    "view;${world};--trajectory;${work}/run.jsonl;--html;${work}/run.html"
    "view;${work}/final.xml;--html;${work}/final.html")
  execute_process(COMMAND ${GRASPKIT} -q ${step} RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "graspkit ${step} failed (${rc}): ${err}")
  endif()
endforeach()
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env NODE_PATH=${NODE_MODULES} HOME=${work}
          ${NODE} ${CMAKE_CURRENT_LIST_DIR}/view_page.cjs ${work}/world.html ${work}/plan.html
          ${CHROMIUM} ${work} ${work}/run.html ${work}/final.html
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the page failed in the browser (screenshots in ${work})")
endif()
