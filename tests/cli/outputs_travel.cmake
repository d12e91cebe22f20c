# Every file graspkit writes loads again from any working folder, with no --root (issue 39):
# a world simulate --out saved, a plan --out (its JSON and its worlds) made with --root, and a
# mesh's Body XML written into another folder by convert -o. Each is written from one folder and
# read back from others; the truth is the round trip: the reloaded world has the bodies where
# simulate left them, each plan world measured again gives the plan's epsilon and contacts, the
# converted body has the mesh's triangles and centre of gravity. A file that is not found is
# reported with each folder searched once.
set(work ${WORK_DIR}/outputs_travel)
file(REMOVE_RECURSE ${work})
file(MAKE_DIRECTORY ${work}/src ${work}/elsewhere ${work}/out/sim ${work}/out/plan ${work}/other)
set(models ${SOURCE_DIR}/models)

# graspkit_in(DIR VAR args...): runs graspkit in DIR with no model root in the environment; it
# must exit 0. Returns its stdout.
function(graspkit_in dir var)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=GRASPKIT_ROOT --unset=GRASPIT
                          ${GRASPKIT} -q ${ARGN}
                  WORKING_DIRECTORY ${dir} OUTPUT_VARIABLE out ERROR_VARIABLE err
                  RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "in ${dir}: graspkit ${ARGN} failed (${rc}): ${out}${err}")
  endif()
  set(${var} "${out}" PARENT_SCOPE)
endfunction()

# A decimal number cut to 5 decimals, "-1" and "-1.0" alike giving "-1.00000".
function(five_decimals out value)
  if(NOT value MATCHES "\\.")
    set(value "${value}.")
  endif()
  string(REGEX REPLACE "^(-?[0-9]+\\.[0-9]*).*" "\\100000" value "${value}")
  string(REGEX REPLACE "^(-?[0-9]+\\.[0-9][0-9][0-9][0-9][0-9]).*" "\\1" value "${value}")
  set(${out} "${value}" PARENT_SCOPE)
endfunction()

# --- simulate --out: a world that needs --root, saved, reloaded elsewhere without it ----------
file(WRITE ${work}/src/drop.xml "<?xml version=\"1.0\" ?>
<world>
  <obstacle>
    <filename>obstacles/floor.xml</filename>
    <transform><fullTransform>(+1 0 0 0)[0 0 0]</fullTransform></transform>
  </obstacle>
  <graspableBody>
    <filename>objects/box.xml</filename>
    <transform><fullTransform>(+1 0 0 0)[0 0 100]</fullTransform></transform>
  </graspableBody>
</world>
")
graspkit_in(${work} report simulate src/drop.xml --root ${models} --seconds 0.3 --json
            --out out/sim/rest.xml)
foreach(dir ${work}/elsewhere ${work}/out/sim /)
  graspkit_in(${dir} info info ${work}/out/sim/rest.xml --json)
  foreach(b 0 1)
    foreach(k 0 1 2)
      string(JSON simulated GET "${report}" bodies ${b} position ${k})
      string(JSON reloaded GET "${info}" bodies ${b} translation ${k})
      five_decimals(s5 "${simulated}")
      five_decimals(r5 "${reloaded}")
      if(NOT s5 STREQUAL r5)
        message(FATAL_ERROR "from ${dir}: body ${b} coordinate ${k} is ${reloaded} reloaded, "
                            "${simulated} as simulate left it")
      endif()
    endforeach()
  endforeach()
endforeach()

# --- plan --out with --root: the JSON and each world, rendered and measured elsewhere ----------
file(READ ${models}/worlds/default.xml default_world)
file(WRITE ${work}/src/mug.xml "${default_world}")  # its names are relative to models/
graspkit_in(${work} plan plan src/mug.xml --root ${models} --steps 1500 --threads 1 --seed 3
            --top 3 --json --out out/plan/plan.json)
file(READ ${work}/out/plan/plan.json saved)
string(JSON schema GET "${saved}" schema_version)
if(schema LESS 3)
  message(FATAL_ERROR "plan --out wrote schema ${schema}")
endif()
# The plan's own file names are relative to its folder, or absolute: each names a file there.
foreach(key world object_file robot_file)
  string(JSON name GET "${saved}" ${key})
  if(NOT IS_ABSOLUTE "${name}")
    set(name ${work}/out/plan/${name})
  endif()
  if(NOT EXISTS "${name}")
    message(FATAL_ERROR "the plan's ${key} names ${name}, which does not exist")
  endif()
endforeach()
string(JSON count LENGTH "${saved}" world_files)
string(JSON grasps LENGTH "${saved}" grasps)
if(count EQUAL 0 OR NOT count EQUAL grasps)
  message(FATAL_ERROR "${count} world files for ${grasps} grasps")
endif()
math(EXPR last "${count} - 1")
foreach(i RANGE ${last})
  string(JSON name GET "${saved}" world_files ${i})
  if(IS_ABSOLUTE "${name}" OR NOT EXISTS ${work}/out/plan/${name})
    message(FATAL_ERROR "world_files ${i} is '${name}', not a file beside the plan")
  endif()
  foreach(dir ${work}/elsewhere /)
    graspkit_in(${dir} measured grasp ${work}/out/plan/${name} --json)
    foreach(key epsilon volume)
      string(JSON planned GET "${saved}" grasps ${i} ${key})
      string(JSON again GET "${measured}" ${key})
      five_decimals(p5 "${planned}")
      five_decimals(a5 "${again}")
      if(NOT p5 STREQUAL a5)
        message(FATAL_ERROR "from ${dir}: ${name} gives ${key} ${again}, the plan ${planned}")
      endif()
    endforeach()
    string(JSON planned GET "${saved}" grasps ${i} contacts)
    string(JSON again LENGTH "${measured}" contacts)
    string(JSON planned_fc GET "${saved}" grasps ${i} force_closure)
    string(JSON again_fc GET "${measured}" force_closure)
    if(NOT planned EQUAL again OR NOT planned_fc STREQUAL again_fc)
      message(FATAL_ERROR "from ${dir}: ${name} gives ${again} contacts (force closure "
                          "${again_fc}), the plan ${planned} (${planned_fc})")
    endif()
  endforeach()
endforeach()
foreach(dir ${work}/elsewhere ${work}/out/plan /)
  file(REMOVE ${work}/elsewhere/sheet.png)
  graspkit_in(${dir} ignored render ${work}/out/plan/plan.json --contacts --size 64x48
              --out ${work}/elsewhere/sheet.png)
  if(NOT EXISTS ${work}/elsewhere/sheet.png)
    message(FATAL_ERROR "render from ${dir} wrote no picture")
  endif()
endforeach()
graspkit_in(${work}/out/plan ignored export plan.json --gltf ${work}/elsewhere/plan.glb)

# --- convert -o OTHER/: the Body XML names its mesh from its own folder -------------------------
file(COPY ${models}/objects/mug.iv DESTINATION ${work}/src)
graspkit_in(${work} ignored convert src/mug.iv -o other/mug.xml --mass 250)
file(READ ${work}/other/mug.xml body)
if(NOT body MATCHES ">\\.\\./src/mug\\.iv</geometryFile>")
  message(FATAL_ERROR "other/mug.xml does not name ../src/mug.iv:\n${body}")
endif()
graspkit_in(${work} mesh info src/mug.iv --json)
foreach(dir ${work}/elsewhere /)
  graspkit_in(${dir} converted info ${work}/other/mug.xml --json)
  string(JSON mass GET "${converted}" bodies 0 mass)
  string(JSON t1 GET "${converted}" bodies 0 triangles)
  string(JSON t2 GET "${mesh}" bodies 0 triangles)
  if(NOT mass EQUAL 250 OR NOT t1 EQUAL t2)
    message(FATAL_ERROR "from ${dir}: mass ${mass}, ${t1} triangles (the mesh has ${t2})")
  endif()
  foreach(k 0 1 2)
    string(JSON c1 GET "${converted}" bodies 0 cog ${k})
    string(JSON c2 GET "${mesh}" bodies 0 cog ${k})
    five_decimals(c1 "${c1}")
    five_decimals(c2 "${c2}")
    if(NOT c1 STREQUAL c2)
      message(FATAL_ERROR "from ${dir}: cog ${k} is ${c1}, the mesh's ${c2}")
    endif()
  endforeach()
endforeach()

# --- not found: each folder searched is listed once --------------------------------------------
file(WRITE ${work}/src/missing.xml "<?xml version=\"1.0\" ?>
<world><graspableBody><filename>objects/nowhere.xml</filename></graspableBody></world>
")
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=GRASPKIT_ROOT --unset=GRASPIT
                        ${GRASPKIT} info src/missing.xml --root src --root ${work}/src/
                WORKING_DIRECTORY ${work} OUTPUT_VARIABLE out ERROR_VARIABLE err
                RESULT_VARIABLE rc)
if(rc EQUAL 0 OR NOT err MATCHES "nowhere.xml' not found")
  message(FATAL_ERROR "a missing model: exit ${rc}: ${err}")
endif()
string(REPLACE "\n" ";" lines "${err}")
set(listed "")
foreach(line ${lines})
  if(line MATCHES "^  (.+)$")
    get_filename_component(folder "${CMAKE_MATCH_1}" ABSOLUTE BASE_DIR ${work})
    list(APPEND listed "${folder}")
  endif()
endforeach()
set(unique ${listed})
list(REMOVE_DUPLICATES unique)
list(LENGTH listed n)
list(LENGTH unique u)
if(n EQUAL 0 OR NOT n EQUAL u)
  message(FATAL_ERROR "the folders searched are not each listed once:\n${err}")
endif()
