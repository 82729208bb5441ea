# Sets SOFTSIM_EIGEN_ALIGN_BYTES: the alignment Eigen gives its fixed-size and heap-allocated
# objects when compiled with the library's flags (64 with AVX-512, 32 with AVX, 16 with SSE).
#
# The value is part of the library's ABI. It sets the layout of fixed-size members such as a
# 12 x 12 element matrix, and how a dynamic matrix's heap block is allocated and freed. A consumer
# compiled without -march=native would otherwise pick 16 and free a vector the library allocated
# 64-aligned with plain free(). The library and everything that links it therefore define
# EIGEN_MAX_ALIGN_BYTES and EIGEN_MAX_STATIC_ALIGN_BYTES to this value (Eigen's documented way
# to make code compiled with different SIMD options compatible). Because it is the value Eigen
# would pick for the library anyway, the library's own code does not change.
include(CheckCXXSourceCompiles)

function(softsim_probe_eigen_alignment arch_flags)
  # The cached check results are keyed by everything that decides the answer.
  string(MD5 key "${CMAKE_CXX_COMPILER};${CMAKE_CXX_FLAGS};${arch_flags}")
  string(SUBSTRING ${key} 0 12 key)
  set(CMAKE_REQUIRED_FLAGS "${arch_flags}")
  set(CMAKE_REQUIRED_LIBRARIES Eigen3::Eigen)
  set(CMAKE_REQUIRED_QUIET ON)
  foreach(bytes 64 32 16 0)
    check_cxx_source_compiles("
#include <Eigen/Core>
static_assert(EIGEN_MAX_STATIC_ALIGN_BYTES == ${bytes} && EIGEN_MAX_ALIGN_BYTES == ${bytes}, \"\");
int main() { return 0; }" SOFTSIM_EIGEN_ALIGN_${bytes}_${key})
    if(SOFTSIM_EIGEN_ALIGN_${bytes}_${key})
      set(SOFTSIM_EIGEN_ALIGN_BYTES ${bytes} PARENT_SCOPE)
      message(STATUS "softsim: Eigen alignment ${bytes} bytes")
      return()
    endif()
  endforeach()
  message(FATAL_ERROR "softsim: could not determine Eigen's alignment for the flags "
                      "'${CMAKE_CXX_FLAGS} ${arch_flags}' (see CMakeFiles/CMakeError.log)")
endfunction()
