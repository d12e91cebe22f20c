# The installed Python module as a user imports it after `cmake --install` (docs/python.md):
#   1. the package lands in the prefix's site-packages folder (PYTHON_DIR below the prefix);
#   2. imported from there (not the build tree), it loads its plugins from the install and plans
#      on the installed models what the build tree's module plans.
# Arguments: -DBUILD_DIR, -DWORK_DIR, -DPYTHON (the interpreter), -DPYTHON_DIR (relative).

set(install ${WORK_DIR}/install)
include(${CMAKE_CURRENT_LIST_DIR}/run.cmake)
fresh_install_test()
set(ENV{PYTHONDONTWRITEBYTECODE} 1)

# 1.
run("cmake --install" COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${install})
file(GLOB module ${install}/${PYTHON_DIR}/graspkit/_graspkit*.so)
foreach(file ${module} ${install}/${PYTHON_DIR}/graspkit/__init__.py
        ${install}/${PYTHON_DIR}/graspkit/_graspkit.pyi ${install}/${PYTHON_DIR}/graspkit/py.typed)
  if(NOT EXISTS ${file})
    message(FATAL_ERROR "the install lacks ${file}")
  endif()
endforeach()
if(NOT module)
  message(FATAL_ERROR "no _graspkit module in ${install}/${PYTHON_DIR}/graspkit")
endif()

# 2.
file(WRITE ${WORK_DIR}/plan.py [=[
import pathlib, sys
import graspkit
models = pathlib.Path(sys.argv[1])
world = graspkit.load_world(models / "worlds/default.xml", roots=[models])
for g in graspkit.plan(world, steps=2000, threads=1, top=3):
    print(f"grasp {g.epsilon:.9f} {g.volume:.9f} {g.contact_count}")
print("package", pathlib.Path(graspkit.__file__).resolve().parent)
for p in graspkit.plugins():  # <prefix>/lib/graspkit/plugins/NAME.so
    print("plugin", pathlib.Path(p["file"]).resolve().parents[3])
]=])
set(ENV{PYTHONPATH} ${BUILD_DIR}/bindings/python)
run("the build tree's module" COMMAND ${PYTHON} ${WORK_DIR}/plan.py ${install}/share/graspkit/models)
string(REGEX MATCHALL "grasp [^\n]*" expected "${out}")
set(ENV{PYTHONPATH} ${install}/${PYTHON_DIR})
run("the installed module" COMMAND ${PYTHON} ${WORK_DIR}/plan.py ${install}/share/graspkit/models)
string(REGEX MATCHALL "grasp [^\n]*" planned "${out}")
if(NOT planned STREQUAL expected OR NOT planned MATCHES "^grasp 0\\.[0-9]+")
  message(FATAL_ERROR "the installed module planned\n${planned}\nthe build tree's\n${expected}")
endif()
file(REAL_PATH ${install} real_install)
string(REGEX MATCH "package [^\n]*" package "${out}")
if(NOT package STREQUAL "package ${real_install}/${PYTHON_DIR}/graspkit")
  message(FATAL_ERROR "imported '${package}', not the installed package")
endif()
string(REGEX MATCHALL "plugin [^\n]*" plugins "${out}")
if(NOT plugins)
  message(FATAL_ERROR "the installed module found no plugins:\n${out}")
endif()
foreach(place ${plugins})
  if(NOT place STREQUAL "plugin ${real_install}")
    message(FATAL_ERROR "the installed module loaded a plugin from outside the install: ${place}")
  endif()
endforeach()
