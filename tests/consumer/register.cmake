# ctest: the consumer project of this folder, built against this build of softsim and run,
# through the installed package (consumer_package) and through add_subdirectory
# (consumer_subdirectory). Same compiler, launcher and build type as this build.
set(consumer_flags "")
if(SOFTSIM_SANITIZE)
  # A sanitized library needs the sanitizer runtime in its consumer's link; the flags are not
  # exported (they are this build's choice), so the consumer adds them itself.
  set(consumer_flags "-fsanitize=address,undefined")
endif()
set(consumer_modes subdirectory)
if(SOFTSIM_INSTALL)
  list(APPEND consumer_modes package)
endif()
# The package mode also runs a Python script on the installed Python package, where one is built.
set(consumer_python "")
if(SOFTSIM_PYTHON)
  set(consumer_python "-DPYTHON=${Python_EXECUTABLE}" "-DPYTHON_INSTALL_DIR=${SOFTSIM_PYTHON_INSTALL_DIR}")
endif()
foreach(mode ${consumer_modes})
  add_test(NAME consumer_${mode}
           COMMAND ${CMAKE_COMMAND} -DMODE=${mode} -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
                   -DBUILD_DIR=${PROJECT_BINARY_DIR} -DWORK_DIR=${PROJECT_BINARY_DIR}/consumer_${mode}
                   -DBUILD_TYPE=${CMAKE_BUILD_TYPE} -DCXX_COMPILER=${CMAKE_CXX_COMPILER}
                   "-DLAUNCHER=${CMAKE_CXX_COMPILER_LAUNCHER}" "-DCXX_FLAGS=${consumer_flags}" ${consumer_python}
                   -P ${PROJECT_SOURCE_DIR}/tests/consumer/run_consumer.cmake)
  set_tests_properties(consumer_${mode} PROPERTIES TIMEOUT 900)
endforeach()
# The subdirectory build compiles the library's core and fe groups a second time, with the
# consumer's flags (about ten minutes on an idle two-core machine, most of the whole ctest run;
# on a busy one it has taken more than 900 s, so it gets twice that): a slow check, run by
# `make test-all`, not by `make test` or CI's `make test-ci`. The package mode reuses this build
# (an install and one source file) and stays in the quick suite.
if(TEST consumer_subdirectory)
  set_tests_properties(consumer_subdirectory PROPERTIES LABELS slow TIMEOUT 1800)
endif()
