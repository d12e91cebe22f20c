# The interpreter the Python module is built for: Debian's /usr/bin/python3, which python3-numpy
# serves (the python3 first on PATH may be pyenv's or a venv's, without NumPy), else the one on
# PATH if it imports NumPy; -DPython3_EXECUTABLE=... decides.
if(NOT DEFINED Python3_EXECUTABLE)
  find_program(GRASPKIT_PATH_PYTHON python3)
  foreach(candidate /usr/bin/python3 ${GRASPKIT_PATH_PYTHON})
    if(EXISTS ${candidate})
      execute_process(COMMAND ${candidate} -c "import numpy" RESULT_VARIABLE no_numpy
                      OUTPUT_QUIET ERROR_QUIET)
      if(no_numpy EQUAL 0)
        set(Python3_EXECUTABLE ${candidate} CACHE FILEPATH "The Python the module is built for")
        break()
      endif()
    endif()
  endforeach()
endif()
find_package(Python3 3.9 COMPONENTS Interpreter Development.Module)
find_package(pybind11 2.10 CONFIG)
if(NOT Python3_FOUND OR NOT pybind11_FOUND)
  message(WARNING "graspkit: no Python module (needs python3-dev, pybind11-dev, python3-numpy)")
  set(GRASPKIT_BUILD_PYTHON OFF)
endif()
