# tests/install/install_test.cmake (cmake -P; tests/install/CMakeLists.txt passes the variables).
# In a directory of its own under WORK_DIR, removed at the end whatever happens:
#   1. cmake --install FRONTIER_BINARY_DIR --prefix <dir>/prefix;
#   2. the package config names neither tree, every `#include "..."` of an installed header
#      names an installed header, and none is a step's internals (core/step/, core/steppers/:
#      core/simulator.h holds them behind a pointer);
#   3. configures examples/step_a_scene with CMAKE_PREFIX_PATH=<dir>/prefix (the same generator,
#      compiler and build type, warnings as errors), builds it and runs it: its exit status is the
#      verdict on the physics it prints;
#   4. docs/library.md shows examples/run_a_scene/main.cpp; built like step_a_scene, its positions
#      of a robot scene after 0.3 s equal those of `frontier run`'s trajectory, digit for digit;
#   5. with PYTHON: the installed Python package imports and gives the same positions.
cmake_minimum_required(VERSION 3.20)

string(RANDOM LENGTH 10 suffix)
set(dir "${WORK_DIR}/install-test-${suffix}")
file(MAKE_DIRECTORY "${dir}")
set(prefix "${dir}/prefix")

# Runs a command; on failure removes `dir` and stops with the command's output.
function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    file(REMOVE_RECURSE "${dir}")
    message(FATAL_ERROR "${what} failed (${status}):\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

run("cmake --install" ${CMAKE_COMMAND} --install "${FRONTIER_BINARY_DIR}" --prefix "${prefix}")

set(include_dir "${prefix}/include/frontier")
file(GLOB_RECURSE headers RELATIVE "${include_dir}" "${include_dir}/*.h")
list(LENGTH headers header_count)
if(header_count EQUAL 0 OR NOT EXISTS "${prefix}/bin/frontier" OR
   NOT EXISTS "${prefix}/lib/cmake/Frontier/FrontierConfig.cmake" OR
   NOT EXISTS "${prefix}/lib/cmake/Frontier/FrontierConfigVersion.cmake")
  file(REMOVE_RECURSE "${dir}")
  message(FATAL_ERROR "the install lacks headers, bin/frontier or the package config")
endif()
# The step's units and steppers stay inside the library.
foreach(header IN LISTS headers)
  if(header MATCHES "^core/(step|steppers)/")
    file(REMOVE_RECURSE "${dir}")
    message(FATAL_ERROR "${header} was installed: a public header includes a step's internals")
  endif()
endforeach()
# The package is relocatable: nothing in it points back into the source or build tree.
file(GLOB package_files "${prefix}/lib/cmake/Frontier/*.cmake")
foreach(file IN LISTS package_files)
  file(READ "${file}" text)
  foreach(tree "${FRONTIER_SOURCE_DIR}" "${FRONTIER_BINARY_DIR}")
    string(FIND "${text}" "${tree}" at)
    if(NOT at EQUAL -1)
      file(REMOVE_RECURSE "${dir}")
      message(FATAL_ERROR "${file} names ${tree}")
    endif()
  endforeach()
endforeach()
foreach(header IN LISTS headers)
  file(STRINGS "${include_dir}/${header}" includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"([^\"]+)\".*$" "\\1" included "${line}")
    if(NOT EXISTS "${include_dir}/${included}")
      file(REMOVE_RECURSE "${dir}")
      message(FATAL_ERROR "installed ${header} includes \"${included}\", which was not installed")
    endif()
  endforeach()
endforeach()

set(configure_args -S "${FRONTIER_SOURCE_DIR}/examples/step_a_scene" -B "${dir}/build" -G "${GENERATOR}"
  "-DCMAKE_PREFIX_PATH=${prefix}" "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}"
  "-DCMAKE_CXX_FLAGS=-Wall -Wextra -Wpedantic -Wshadow -Werror")
if(CXX_COMPILER_LAUNCHER)
  list(APPEND configure_args "-DCMAKE_CXX_COMPILER_LAUNCHER=${CXX_COMPILER_LAUNCHER}")
endif()
run("configuring examples/step_a_scene" ${CMAKE_COMMAND} ${configure_args})
run("building examples/step_a_scene" ${CMAKE_COMMAND} --build "${dir}/build")
run("running step_a_scene" "${dir}/build/step_a_scene")
message(STATUS "${header_count} headers installed; step_a_scene:\n${last_output}")

# 4. docs/library.md's minimal program is examples/run_a_scene/main.cpp, word for word; built
#    against the package, it ends a robot scene where `frontier run` does, to the last bit.
file(READ "${FRONTIER_SOURCE_DIR}/examples/run_a_scene/main.cpp" program)
file(READ "${FRONTIER_SOURCE_DIR}/docs/library.md" library_doc)
string(FIND "${library_doc}" "${program}" at)
if(at EQUAL -1)
  file(REMOVE_RECURSE "${dir}")
  message(FATAL_ERROR "docs/library.md does not show examples/run_a_scene/main.cpp as it is")
endif()
list(TRANSFORM configure_args REPLACE "examples/step_a_scene$" "examples/run_a_scene")
list(TRANSFORM configure_args REPLACE "^${dir}/build$" "${dir}/build-run")
run("configuring examples/run_a_scene" ${CMAKE_COMMAND} ${configure_args})
run("building examples/run_a_scene" ${CMAKE_COMMAND} --build "${dir}/build-run")
set(scene "${FRONTIER_SOURCE_DIR}/scenes/robots/quadruped_stand.yaml")
run("frontier run" "${prefix}/bin/frontier" run "${scene}" --duration 0.3 --quiet
    --trajectory "${dir}/trajectory.csv")
run("running run_a_scene" "${dir}/build-run/run_a_scene" "${scene}" 0.3)
string(STRIP "${last_output}" printed)
string(REPLACE "\n" ";" printed "${printed}")
file(READ "${dir}/trajectory.csv" trajectory)
list(LENGTH printed body_count)
if(body_count LESS 13)
  file(REMOVE_RECURSE "${dir}")
  message(FATAL_ERROR "run_a_scene printed ${body_count} bodies, the quadruped has 13:\n${last_output}")
endif()
foreach(line IN LISTS printed)
  string(FIND "${trajectory}" "\n${line}," at)
  if(at EQUAL -1)
    file(REMOVE_RECURSE "${dir}")
    message(FATAL_ERROR "run_a_scene printed '${line}', which no row of `frontier run`'s trajectory begins with")
  endif()
endforeach()
message(STATUS "run_a_scene ends where frontier run does (${body_count} bodies)")

# 5. The Python package where the install put it (PYTHON_SITE under the prefix), nothing of the
#    build folder on the path: it imports, and its positions after 0.3 s are the trajectory's.
if(PYTHON)
  set(check "import frontier, sys
sim = frontier.load(sys.argv[1])
sim.step(round(0.3 / sim.dt))
for name, p, static in zip(sim.body_names, sim.positions, sim.is_static):
    if not static:
        print('%.17g' % sim.time, name, *['%.17g' % x for x in p])")
  run("importing the installed Python package" ${CMAKE_COMMAND} -E env --unset=PYTHONPATH
      "PYTHONPATH=${prefix}/${PYTHON_SITE}" "${PYTHON}" -c "${check}" "${scene}")
  string(STRIP "${last_output}" printed)
  string(REPLACE "\n" ";" printed "${printed}")
  foreach(line IN LISTS printed)
    string(REPLACE " " ";" fields "${line}")
    list(GET fields 0 time)
    list(GET fields 1 name)
    list(GET fields 2 x)
    list(GET fields 3 y)
    list(GET fields 4 z)
    string(FIND "${trajectory}" "\n${time},${name},${x},${y},${z}," at)
    if(at EQUAL -1)
      file(REMOVE_RECURSE "${dir}")
      message(FATAL_ERROR "the installed Python package puts ${name} at ${x} ${y} ${z} at t = ${time} s, where no row of `frontier run`'s trajectory does")
    endif()
  endforeach()
  message(STATUS "the installed Python package imports and ends where frontier run does")
endif()
file(REMOVE_RECURSE "${dir}")
