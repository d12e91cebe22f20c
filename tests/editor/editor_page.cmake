# Drives graspkit serve in headless Chromium (editor_page.cjs) on GraspIt!'s plannerMug. Skipped
# loudly where the corpus, Chromium or the page's node_modules are missing.
if(NOT EXISTS ${SHARED_DIR}/graspit-data/worlds/plannerMug.xml)
  message(WARNING "SKIPPED: ${SHARED_DIR}/graspit-data is absent")
  return()
endif()
if(NOT EXISTS "${CHROMIUM}" OR NOT EXISTS "${NODE_MODULES}/puppeteer-core")
  message(WARNING "SKIPPED: no Chromium ('${CHROMIUM}') or no viewer node_modules ('${NODE_MODULES}')")
  return()
endif()
set(work ${WORK_DIR}/editor)
file(REMOVE_RECURSE ${work})
file(MAKE_DIRECTORY ${work})
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env NODE_PATH=${NODE_MODULES} HOME=${work}
          ${NODE} ${CMAKE_CURRENT_LIST_DIR}/editor_page.cjs ${GRASPKIT}
          ${SHARED_DIR}/graspit-data/worlds/plannerMug.xml ${CHROMIUM} ${work}
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the editor failed in the browser (screenshots in ${work})")
endif()
