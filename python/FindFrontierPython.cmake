# Finds the Python interpreter and pybind11 the module is built for; sets FRONTIER_PYTHON_FOUND.
# Debian's python3-numpy, python3-pytest and pybind11-dev serve Debian's /usr/bin/python3, which is
# taken over any other python3 on PATH (a pyenv, a virtual environment without NumPy); give
# -DPython3_EXECUTABLE=... to build for another interpreter.
if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python3_EXECUTABLE /usr/bin/python3)
endif()
find_package(Python3 COMPONENTS Interpreter Development.Module)
if(Python3_FOUND)
  find_package(pybind11 2.6 CONFIG QUIET)
endif()
if(Python3_FOUND AND pybind11_FOUND)
  set(FRONTIER_PYTHON_FOUND ON)
  message(STATUS "Python module: for ${Python3_EXECUTABLE} (${Python3_VERSION}), pybind11 ${pybind11_VERSION}")
else()
  set(FRONTIER_PYTHON_FOUND OFF)
  message(STATUS "Python module: not built (needs python3-dev and pybind11-dev: scripts/install-deps.sh)")
endif()
