# The Rust crate (bindings/rust), built offline with Debian's cargo and rustc against this build's
# libgraspkit_c: `cargo test` (its own tests), then its example on GraspIt!'s plannerMug, whose
# output must be what `graspkit grasp --autograsp` prints.
# Arguments: -DCARGO, -DRUSTC, -DSOURCE_DIR, -DLIB_DIR (libgraspkit_c's folder), -DGRASPKIT (the
# CLI), -DSHARED_DIR, -DWORK_DIR (cargo's target folder).

set(manifest ${SOURCE_DIR}/bindings/rust/Cargo.toml)
get_filename_component(bin ${RUSTC} DIRECTORY)
set(env ${CMAKE_COMMAND} -E env GRASPKIT_LIB_DIR=${LIB_DIR} RUSTC=${RUSTC} RUSTDOC=${bin}/rustdoc CARGO_TARGET_DIR=${WORK_DIR}
        CARGO_HOME=${WORK_DIR}/cargo-home GRASPKIT_SHARED=${SHARED_DIR})

execute_process(COMMAND ${env} ${CARGO} test --offline --manifest-path ${manifest}
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
message(STATUS "${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cargo test failed (${rc}):\n${out}\n${err}")
endif()
if(out MATCHES "SKIPPED" OR err MATCHES "SKIPPED")
  message(FATAL_ERROR "the crate's tests skipped GraspIt!'s corpus (${SHARED_DIR}):\n${out}\n${err}")
endif()

set(world ${SHARED_DIR}/graspit-data/worlds/plannerMug.xml)
set(root ${SHARED_DIR}/graspit-data)
execute_process(COMMAND ${GRASPKIT} grasp ${world} --autograsp --root ${root}
                OUTPUT_VARIABLE cli RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "graspkit grasp failed (${rc})")
endif()
set(expected "")
foreach(pattern "[0-9]+ contacts with the object" "epsilon [^\n]+" "volume [^\n]+" "force closure [a-z]+")
  string(REGEX MATCH "${pattern}" line "${cli}")
  string(APPEND expected "${line}\n")
endforeach()
execute_process(COMMAND ${env} ${CARGO} run --offline --quiet --manifest-path ${manifest}
                        --example plannermug -- ${world} ${root}
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR NOT out STREQUAL expected)
  message(FATAL_ERROR "the Rust example printed (${rc})\n${out}\n${err}\ngraspkit grasp printed\n${expected}")
endif()
message(STATUS "the Rust example prints what graspkit grasp prints:\n${out}")
