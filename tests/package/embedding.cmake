# Host programs embedding graspkit from an install, as docs/embedding.md tells a user to build
# them: the C host (examples/embed_c) through CMake and through pkg-config with the C compiler
# alone, and the C++ host (examples/embed_cpp) through CMake. Each closes the first hand of
# GraspIt!'s plannerMug and prints the grasp; what they print must be what the installed
# `graspkit grasp --autograsp` prints, and GraspIt!'s figures (6 contacts, volume 0.0039213).
# Arguments: -DBUILD_DIR, -DSOURCE_DIR, -DSHARED_DIR, -DWORK_DIR, -DGENERATOR, -DC_COMPILER,
# -DCXX_COMPILER, -DSANITIZE.

set(install ${WORK_DIR}/install)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

include(${CMAKE_CURRENT_LIST_DIR}/run.cmake)

run("cmake --install" COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${install})
foreach(file include/graspkit.h lib/libgraspkit_c.so lib/libgraspkit_lua.so
             include/graspkit/lua/script_host.hpp lib/pkgconfig/graspkit.pc
             lib/pkgconfig/graspkit-c.pc)
  if(NOT EXISTS ${install}/${file})
    message(FATAL_ERROR "the install lacks ${file}")
  endif()
endforeach()
file(READ ${install}/lib/pkgconfig/graspkit-c.pc pc)
if(NOT pc MATCHES "prefix=${install}\n")
  message(FATAL_ERROR "graspkit-c.pc does not name the install's prefix ${install}:\n${pc}")
endif()

set(world ${SHARED_DIR}/graspit-data/worlds/plannerMug.xml)
set(root ${SHARED_DIR}/graspit-data)
if(NOT EXISTS ${world})
  message(FATAL_ERROR "${world} not found: the embedding test needs ../shared (CI has it)")
endif()

set(flags "")
set(options -DCMAKE_PREFIX_PATH=${install} -DCMAKE_BUILD_TYPE=RelWithDebInfo
            -DCMAKE_C_COMPILER=${C_COMPILER} -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
if(GENERATOR)
  list(APPEND options -G ${GENERATOR})
endif()
if(SANITIZE)
  # libgraspkit_c is C++: under UBSan it calls the runtime's C++ part, which clang links into a
  # C program only when asked, with libstdc++ under it (gcc's libubsan holds both).
  set(link_flags -fsanitize=address,undefined)
  if(C_COMPILER MATCHES "clang")
    list(APPEND link_flags -fsanitize-link-c++-runtime -lstdc++)
  endif()
  set(flags -fsanitize=address,undefined -fno-omit-frame-pointer ${link_flags})
  list(JOIN link_flags " " link_flags)
  list(APPEND options "-DCMAKE_C_FLAGS=-fsanitize=address,undefined -fno-omit-frame-pointer"
       "-DCMAKE_CXX_FLAGS=-fsanitize=address,undefined -fno-omit-frame-pointer"
       "-DCMAKE_EXE_LINKER_FLAGS=${link_flags}")
endif()

# The reference: the installed program.
run("graspkit grasp" COMMAND ${install}/bin/graspkit grasp ${world} --autograsp --root ${root})
set(expected "")
foreach(pattern "[0-9]+ contacts with the object" "epsilon [^\n]+" "volume [^\n]+" "force closure [a-z]+")
  string(REGEX MATCH "${pattern}" line "${out}")
  if(NOT line)
    message(FATAL_ERROR "graspkit grasp printed no '${pattern}':\n${out}")
  endif()
  string(APPEND expected "${line}\n")
endforeach()
if(NOT expected MATCHES "^6 contacts with the object\nepsilon -1\nvolume 0\\.003921")
  message(FATAL_ERROR "graspkit grasp does not give GraspIt!'s figures:\n${expected}")
endif()

function(check_host what program)
  run("${what}" COMMAND ${program} ${world} ${root})
  # stdout holds the grasp and nothing else (the library's warnings go to stderr).
  if(NOT out STREQUAL expected)
    message(FATAL_ERROR "${what} printed\n${out}\ngraspkit grasp printed\n${expected}")
  endif()
  message(STATUS "${what}: same contacts, epsilon and volume as graspkit grasp")
endfunction()

foreach(host embed_c embed_cpp)
  run("configuring ${host}" COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/${host}
      -B ${WORK_DIR}/${host} ${options})
  run("building ${host}" COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/${host})
  check_host("${host} (CMake)" ${WORK_DIR}/${host}/grasp_report)
endforeach()

# The C host with pkg-config and the compiler alone: graspkit-c.pc must be enough.
find_program(PKG_CONFIG pkg-config REQUIRED)
execute_process(COMMAND ${CMAKE_COMMAND} -E env PKG_CONFIG_PATH=${install}/lib/pkgconfig
                        ${PKG_CONFIG} --cflags --libs graspkit-c
                OUTPUT_VARIABLE pc_flags OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pkg-config does not know graspkit-c")
endif()
separate_arguments(pc_flags)
run("cc with pkg-config" COMMAND ${C_COMPILER} -std=c99 -pedantic -Wall -Werror ${flags}
    ${SOURCE_DIR}/examples/embed_c/grasp_report.c ${pc_flags} -Wl,-rpath,${install}/lib
    -o ${WORK_DIR}/grasp_report_pc)
check_host("embed_c (pkg-config)" ${WORK_DIR}/grasp_report_pc)
