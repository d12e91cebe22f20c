# render, export and view run as a user would on GraspIt!'s plannerMug and on a plan of it: the
# PNG's size from its header, a contact sheet's size from the grasp count, the .glb's magic, the
# page's embedded scene, world:render from Lua, and bad input refused with a message.
if(NOT EXISTS ${SHARED_DIR}/graspit-data/worlds/plannerMug.xml)
  message(WARNING "SKIPPED: ${SHARED_DIR}/graspit-data is absent")
  return()
endif()
set(world ${SHARED_DIR}/graspit-data/worlds/plannerMug.xml)
set(work ${WORK_DIR}/pictures)
file(REMOVE_RECURSE ${work})
file(MAKE_DIRECTORY ${work})

function(graspkit_ok)
  execute_process(COMMAND ${GRASPKIT} -q ${ARGN} WORKING_DIRECTORY ${work}
                  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "graspkit ${ARGN} failed (${rc}): ${out}${err}")
  endif()
endfunction()

# graspkit_fails(STATUS TEXT args...): exits with STATUS and says TEXT on stderr.
function(graspkit_fails status text)
  execute_process(COMMAND ${GRASPKIT} ${ARGN} WORKING_DIRECTORY ${work}
                  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL status)
    message(FATAL_ERROR "graspkit ${ARGN}: exit ${rc}, expected ${status}: ${err}")
  endif()
  string(FIND "${err}" "${text}" at)
  if(at LESS 0)
    message(FATAL_ERROR "graspkit ${ARGN}: expected '${text}' in: ${err}")
  endif()
endfunction()

# The width and height a PNG's IHDR records (bytes 16-23, big-endian).
function(png_size file width_var height_var)
  file(READ ${file} head LIMIT 24 HEX)
  string(SUBSTRING "${head}" 0 16 magic)
  if(NOT magic STREQUAL "89504e470d0a1a0a")
    message(FATAL_ERROR "${file} is not a PNG (${magic})")
  endif()
  string(SUBSTRING "${head}" 32 8 w)
  string(SUBSTRING "${head}" 40 8 h)
  math(EXPR w "0x${w}")
  math(EXPR h "0x${h}")
  set(${width_var} ${w} PARENT_SCOPE)
  set(${height_var} ${h} PARENT_SCOPE)
endfunction()

graspkit_ok(render ${world} --out world.png --size 321x123)
png_size(${work}/world.png w h)
if(NOT w EQUAL 321 OR NOT h EQUAL 123)
  message(FATAL_ERROR "world.png is ${w}x${h}, asked for 321x123")
endif()

# A plan, then its contact sheet: ceil(sqrt(n)) columns, 4-pixel gaps.
graspkit_ok(plan ${world} --steps 1500 --threads 1 --seed 3 --top 5 --out ${work}/plan.json)
file(READ ${work}/plan.json plan)
string(JSON count LENGTH "${plan}" grasps)
graspkit_ok(render plan.json --out sheet.png --size 100x80 --contacts)
png_size(${work}/sheet.png w h)
set(columns 1)
while(columns LESS count AND columns LESS 5)
  math(EXPR square "${columns} * ${columns}")
  if(square GREATER_EQUAL count)
    break()
  endif()
  math(EXPR columns "${columns} + 1")
endwhile()
math(EXPR rows "(${count} + ${columns} - 1) / ${columns}")
math(EXPR expected_w "${columns} * 100 + (${columns} - 1) * 4")
math(EXPR expected_h "${rows} * 80 + (${rows} - 1) * 4")
if(NOT w EQUAL expected_w OR NOT h EQUAL expected_h)
  message(FATAL_ERROR "sheet of ${count} grasps is ${w}x${h}, expected ${expected_w}x${expected_h}")
endif()
graspkit_ok(render plan.json --grasp 1 --out one.png --size 64x48)
png_size(${work}/one.png w h)
if(NOT w EQUAL 64 OR NOT h EQUAL 48)
  message(FATAL_ERROR "one.png is ${w}x${h}")
endif()

# glTF: the binary container's magic, "glTF".
graspkit_ok(export plan.json --gltf plan.glb)
file(READ ${work}/plan.glb magic LIMIT 4 HEX)
if(NOT magic STREQUAL "676c5446")
  message(FATAL_ERROR "plan.glb does not start with glTF: '${magic}'")
endif()

# Its JSON chunk (length at bytes 12-15, little-endian; text from byte 20): one scene per grasp,
# and the contacts found again on each saved grasp world are as many as the plan measured (the
# round trip of plan --out's worlds).
file(READ ${work}/plan.glb length_hex OFFSET 12 LIMIT 4 HEX)
string(REGEX REPLACE "^(..)(..)(..)(..)$" "\\4\\3\\2\\1" length_hex "${length_hex}")
math(EXPR length "0x${length_hex}")
file(READ ${work}/plan.glb gltf OFFSET 20 LIMIT ${length})
string(JSON scenes LENGTH "${gltf}" scenes)
if(NOT scenes EQUAL count)
  message(FATAL_ERROR "plan.glb has ${scenes} scenes for ${count} grasps")
endif()
math(EXPR last "${count} - 1")
foreach(i RANGE ${last})
  string(JSON planned GET "${plan}" grasps ${i} contacts)
  string(JSON found LENGTH "${gltf}" scenes ${i} extras contacts)
  string(JSON name GET "${gltf}" scenes ${i} name)
  math(EXPR rank "${i} + 1")
  if(NOT found EQUAL planned OR NOT name STREQUAL "grasp ${rank}")
    message(FATAL_ERROR "scene ${i} ('${name}'): ${found} contacts on the saved world, the plan measured ${planned}")
  endif()
endforeach()

# The page: the scene and the viewer inside, nothing fetched from the network.
execute_process(COMMAND ${GRASPKIT} -q view plan.json --html plan.html WORKING_DIRECTORY ${work}
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(rc EQUAL 0)
  file(READ ${work}/plan.html page)
  foreach(part "id=\"graspkit-scene\"" "id=\"graspkit-meta\"" "graspkitViewer")
    string(FIND "${page}" "${part}" at)
    if(at LESS 0)
      message(FATAL_ERROR "plan.html lacks ${part}")
    endif()
  endforeach()
  foreach(remote "src=\"http" "import(\"http" "https://unpkg" "https://cdn")
    string(FIND "${page}" "${remote}" at)
    if(at GREATER_EQUAL 0)
      message(FATAL_ERROR "plan.html loads something from the network: ${remote}")
    endif()
  endforeach()
else()
  string(FIND "${err}" "built without the web viewer" at)
  if(at LESS 0)
    message(FATAL_ERROR "view failed (${rc}): ${err}")
  endif()
endif()

# Lua: world:render writes the same kind of file.
file(WRITE ${work}/render.lua
  "local w = graspkit.load_world(arg[1])\n"
  "assert(w:render{out = 'lua.png', width = 90, height = 70, contacts = true}:match('lua.png$'))\n"
  "local ok, err = pcall(function() w:render{out = 'x.png', camera = 'sideways'} end)\n"
  "assert(not ok and tostring(err):find('sideways'), tostring(err))\n"
  "ok, err = pcall(function() w:render{} end)\n"
  "assert(not ok and tostring(err):find('out'), tostring(err))\n")
graspkit_ok(run render.lua --allow-write ${work} --allow-read ${SHARED_DIR} -- ${world})
png_size(${work}/lua.png w h)
if(NOT w EQUAL 90 OR NOT h EQUAL 70)
  message(FATAL_ERROR "lua.png is ${w}x${h}")
endif()

# Bad input: a message naming what is wrong, exit 1 (2 for usage), no file left behind.
graspkit_fails(1 "--size" render ${world} --out bad.png --size 0x10)
graspkit_fails(1 "--size" render ${world} --out bad.png --size big)
graspkit_fails(1 "sideways" render ${world} --out bad.png --camera sideways)
graspkit_fails(1 "--grasp 99" render plan.json --grasp 99 --out bad.png)
graspkit_fails(1 "--grasp" render ${world} --grasp 1 --out bad.png)
graspkit_fails(1 "no/such" render ${world} --out no/such/folder.png)
graspkit_fails(2 "--samples" render ${world} --out bad.png --samples 9)
file(WRITE ${work}/broken.json "{ \"grasps\": [ ")
graspkit_fails(1 "not valid JSON" render ${work}/broken.json --out bad.png)
file(WRITE ${work}/list.json "[]")
graspkit_fails(1 "not a plan" view ${work}/list.json --html bad.html)
file(WRITE ${work}/odd.json "{\"world\": \"${world}\", \"robot\": \"Barrett\", \"grasps\": [{\"x\": 1}]}")
graspkit_fails(1 "grasps[0]" render ${work}/odd.json --out bad.png)
graspkit_fails(1 "grasps[0]" export ${work}/odd.json --gltf bad.glb)
graspkit_fails(1 "64 million pixels" render plan.json --size 4000x4000 --out bad.png)
# A plan with no grasps is named as such (it crashed view --html), and poses in a plan name a
# rotation: a zero quaternion is refused, not taken as the identity.
file(WRITE ${work}/empty.json "{\"world\": \"${world}\", \"robot\": \"Barrett\", \"grasps\": []}")
graspkit_fails(1 "no grasps" view ${work}/empty.json --html bad.html)
graspkit_fails(1 "no grasps" render ${work}/empty.json --out bad.png)
file(WRITE ${work}/zero.json "{\"world\": \"${world}\", \"robot\": \"Barrett\", \"grasps\": [{\"pose\": {\"world\": {\"translation\": [0, 0, 0], \"quaternion\": [0, 0, 0, 0]}}, \"dofs\": [0, 0, 0, 0]}]}")
graspkit_fails(1 "names no rotation" render ${work}/zero.json --out bad.png)
# Outputs replace only regular files.
graspkit_fails(1 "not a regular file" render ${world} --out /dev/null)
if(EXISTS ${work}/bad.png OR EXISTS ${work}/bad.html OR EXISTS ${work}/bad.glb)
  message(FATAL_ERROR "a failed render left bad.png behind")
endif()
