# Builds and runs the consumer project of this folder against softsim (cmake -P; ctest runs it
# as consumer_package and consumer_subdirectory, see register.cmake). Fails on the first step
# that fails.
#   MODE=package       cmake --install BUILD_DIR into WORK_DIR/prefix, then find_package(softsim)
#   MODE=subdirectory  add_subdirectory(SOURCE_DIR) from the consumer
# Both check that the consumer's own compile line carries none of softsim's private flags
# (-march=native, sanitizers): they must not leak through the usage requirements.
# With PYTHON (and PYTHON_INSTALL_DIR) the package mode also runs use_installed.py on the
# installed Python package.
# Variables: MODE, SOURCE_DIR, BUILD_DIR, WORK_DIR, BUILD_TYPE, CXX_COMPILER, LAUNCHER, CXX_FLAGS
# (CXX_FLAGS: what the consumer itself must add, e.g. the sanitizer runtime of a sanitized build).
cmake_minimum_required(VERSION 3.18)

foreach(var MODE SOURCE_DIR WORK_DIR CXX_COMPILER)
  if(NOT ${var})
    message(FATAL_ERROR "run_consumer.cmake: -D${var}=... is required")
  endif()
endforeach()

function(step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "consumer (${MODE}): ${what} failed (${rc}):\n${out}")
  endif()
  message(STATUS "consumer (${MODE}): ${what}: ok")
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(configure_args -S ${SOURCE_DIR}/tests/consumer -B ${WORK_DIR}/build
    -DCMAKE_BUILD_TYPE=${BUILD_TYPE} -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
    "-DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER}" "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}"
    -DCMAKE_EXPORT_COMPILE_COMMANDS=ON)

if(MODE STREQUAL "package")
  if(NOT BUILD_DIR)
    message(FATAL_ERROR "run_consumer.cmake: -DBUILD_DIR=... is required for MODE=package")
  endif()
  set(prefix ${WORK_DIR}/prefix)
  step("cmake --install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
  # What the install must hold besides the package itself (which find_package checks).
  file(GLOB_RECURSE targets_files ${prefix}/*/cmake/softsim/softsimTargets*.cmake)
  foreach(expected include/softsim/version.hpp include/softsim/fem/assembly.hpp bin/dhd_sim bin/mesher)
    if(NOT EXISTS ${prefix}/${expected})
      message(FATAL_ERROR "consumer (package): the install lacks ${expected}")
    endif()
  endforeach()
  if(NOT targets_files)
    message(FATAL_ERROR "consumer (package): the install lacks lib/cmake/softsim/softsimTargets.cmake")
  endif()
  foreach(file ${targets_files})
    file(READ ${file} exported)
    if(exported MATCHES "-march|-fsanitize")
      message(FATAL_ERROR "consumer (package): ${file} exports a private flag (${CMAKE_MATCH_0})")
    endif()
  endforeach()
  list(APPEND configure_args -DCMAKE_PREFIX_PATH=${prefix})
elseif(MODE STREQUAL "subdirectory")
  list(APPEND configure_args -DSOFTSIM_SOURCE_TREE=${SOURCE_DIR})
else()
  message(FATAL_ERROR "run_consumer.cmake: MODE must be package or subdirectory, not '${MODE}'")
endif()

step("configure" ${CMAKE_COMMAND} ${configure_args})
step("build" ${CMAKE_COMMAND} --build ${WORK_DIR}/build -j 2)

# The compile lines, one "command" line per source file.
file(STRINGS ${WORK_DIR}/build/compile_commands.json commands REGEX "\"command\"")
set(consumer_line "")
foreach(line ${commands})
  if(line MATCHES "tests/consumer/main\\.cpp")
    set(consumer_line "${line}")
  elseif(line MATCHES "/tests/cpp/|/cpp/bench/")
    message(FATAL_ERROR "consumer (${MODE}): softsim added its tests or benchmarks to a consumer's build")
  elseif(MODE STREQUAL "subdirectory" AND line MATCHES "/cpp/softsim/" AND NOT line MATCHES "-march=native")
    # softsim's default (SOFTSIM_NATIVE) still applies to its own sources: the check below sees flags.
    message(FATAL_ERROR "consumer (subdirectory): softsim's own source compiled without -march=native:\n${line}")
  endif()
endforeach()
if(NOT consumer_line)
  message(FATAL_ERROR "consumer (${MODE}): no compile line for main.cpp in compile_commands.json")
endif()
# -fno-sanitize-recover and fuzzer-no-link come only from softsim's SOFTSIM_SANITIZE and SOFTSIM_FUZZ.
if(consumer_line MATCHES "-march|-fno-sanitize-recover|fuzzer-no-link")
  message(FATAL_ERROR "consumer (${MODE}): softsim's private flags reached the consumer:\n${consumer_line}")
endif()

step("run" ${WORK_DIR}/build/uniaxial_consumer)
message("${step_output}")

# The Python package of the same install, imported from the prefix alone (run from WORK_DIR, so
# nothing of the source or build tree is on the path).
if(MODE STREQUAL "package" AND PYTHON)
  if(IS_ABSOLUTE "${PYTHON_INSTALL_DIR}")
    set(python_dir ${PYTHON_INSTALL_DIR})
  else()
    set(python_dir ${prefix}/${PYTHON_INSTALL_DIR})
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${python_dir} PYTHONNOUSERSITE=1
                          ${PYTHON} ${SOURCE_DIR}/tests/consumer/use_installed.py ${python_dir}
                  WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "consumer (package): the installed Python package failed (${rc}):\n${out}")
  endif()
  message("${out}")
endif()
