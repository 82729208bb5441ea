# cmake --install: headers under include/softsim/, the static libraries, the executables, and
# the package softsim (lib/cmake/softsim/) whose targets are softsim::core, softsim::fe,
# softsim::meshless, softsim::fit, softsim::multirate, softsim::haptic, softsim::meshing (surface meshing
# through libgmsh) and softsim::softsim (all of them but meshing).
include(CMakePackageConfigHelpers)

set(SOFTSIM_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/softsim)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/cpp/softsim/
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/softsim
        FILES_MATCHING PATTERN "*.hpp")
install(FILES ${PROJECT_BINARY_DIR}/generated/softsim/version.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/softsim)

set(SOFTSIM_LIBRARY_TARGETS softsim)
foreach(group ${SOFTSIM_GROUPS})
  list(APPEND SOFTSIM_LIBRARY_TARGETS softsim_${group})
endforeach()
install(TARGETS ${SOFTSIM_LIBRARY_TARGETS} EXPORT softsimTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS ${SOFTSIM_APPS} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

install(EXPORT softsimTargets NAMESPACE softsim:: DESTINATION ${SOFTSIM_CMAKE_DIR})
# The config finds again what the exported link interface names; OpenMP only where it was used.
set(SOFTSIM_WITH_OPENMP OFF)
if(OpenMP_CXX_FOUND)
  set(SOFTSIM_WITH_OPENMP ON)
endif()
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/softsimConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/package/softsimConfig.cmake
                              INSTALL_DESTINATION ${SOFTSIM_CMAKE_DIR})
# 0.x: a minor release may change the interface.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/package/softsimConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/package/softsimConfig.cmake
              ${PROJECT_BINARY_DIR}/package/softsimConfigVersion.cmake
        DESTINATION ${SOFTSIM_CMAKE_DIR})
