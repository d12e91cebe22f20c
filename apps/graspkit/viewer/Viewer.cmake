# The web pages: `graspkit view`'s (src/viewer.js) and `graspkit serve`'s (src/editor.js), each
# bundled with three.js (npm) by esbuild into one script, compiled into the program as
# kViewerScript and kEditorScript. npm installs the exact versions of
# package-lock.json into the build folder (nothing is fetched at view time). Without node and npm
# (or with GRASPKIT_BUILD_VIEWER off) both are null and `graspkit view` and `serve` say so.
set(viewer_source ${CMAKE_CURRENT_SOURCE_DIR}/viewer)
set(viewer_build ${CMAKE_CURRENT_BINARY_DIR}/viewer)
find_program(GRASPKIT_NODE node)
find_program(GRASPKIT_NPM npm)
if(GRASPKIT_BUILD_VIEWER AND GRASPKIT_NODE AND GRASPKIT_NPM)
  set(viewer_inputs package.json package-lock.json build.mjs src/viewer.js src/editor.js)
  set(viewer_copies)
  foreach(input IN LISTS viewer_inputs)
    add_custom_command(OUTPUT ${viewer_build}/${input}
      COMMAND ${CMAKE_COMMAND} -E copy ${viewer_source}/${input} ${viewer_build}/${input}
      DEPENDS ${viewer_source}/${input})
    list(APPEND viewer_copies ${viewer_build}/${input})
  endforeach()
  add_custom_command(OUTPUT ${viewer_build}/node_modules/.package-lock.json
    COMMAND ${GRASPKIT_NPM} ci --no-audit --no-fund --loglevel=error
    WORKING_DIRECTORY ${viewer_build}
    DEPENDS ${viewer_build}/package.json ${viewer_build}/package-lock.json
    COMMENT "npm ci: three.js and esbuild for the viewer")
  add_custom_command(OUTPUT ${viewer_build}/viewer_script.cpp
    COMMAND ${GRASPKIT_NODE} build.mjs viewer_script.cpp
    WORKING_DIRECTORY ${viewer_build}
    DEPENDS ${viewer_copies} ${viewer_build}/node_modules/.package-lock.json
    COMMENT "Bundling the viewer (three.js + viewer.js)")
  add_custom_command(OUTPUT ${viewer_build}/editor_script.cpp
    COMMAND ${GRASPKIT_NODE} build.mjs editor_script.cpp editor.js kEditorScript
    WORKING_DIRECTORY ${viewer_build}
    DEPENDS ${viewer_copies} ${viewer_build}/node_modules/.package-lock.json
    COMMENT "Bundling the editor page (three.js + editor.js)")
  set(GRASPKIT_VIEWER_SOURCE ${viewer_build}/viewer_script.cpp)
  set(GRASPKIT_EDITOR_SOURCE ${viewer_build}/editor_script.cpp)
  # The browser test (tests/viewer) runs puppeteer-core from these node_modules.
  set(GRASPKIT_VIEWER_NODE_MODULES ${viewer_build}/node_modules CACHE INTERNAL "")
else()
  file(WRITE ${viewer_build}/viewer_none.cpp
    "namespace graspkit::cli {\nextern const char* const kViewerScript;\n"
    "const char* const kViewerScript = nullptr;  // built without node/npm\n"
    "extern const char* const kEditorScript;\n"
    "const char* const kEditorScript = nullptr;\n}\n")
  set(GRASPKIT_VIEWER_SOURCE ${viewer_build}/viewer_none.cpp)
  set(GRASPKIT_EDITOR_SOURCE "")
  set(GRASPKIT_VIEWER_NODE_MODULES "" CACHE INTERNAL "")
  message(STATUS "graspkit view: no web viewer (GRASPKIT_BUILD_VIEWER off, or node/npm missing)")
endif()
