# Finds pdk's dependencies and collects them in the interface target pdk_deps.
# Each missing one stops configuration with the Debian package that provides it.
include_guard(GLOBAL)
include(CMakeFindDependencyMacro)

macro(_pdk_missing what pkg)
  message(FATAL_ERROR "pdk: ${what} not found. Install it with:\n  apt-get install -y ${pkg}\n"
                      "(the README's first command installs every dependency)")
endmacro()

find_package(OpenMP QUIET COMPONENTS C)
if(NOT OpenMP_C_FOUND)
  _pdk_missing("OpenMP for C" "libomp-dev (or use gcc, which ships libgomp)")
endif()

find_package(PkgConfig QUIET)
if(NOT PkgConfig_FOUND)
  _pdk_missing("pkg-config" "pkg-config")
endif()
pkg_check_modules(HWLOC QUIET IMPORTED_TARGET GLOBAL hwloc>=2.0)
if(NOT HWLOC_FOUND)
  _pdk_missing("hwloc >= 2.0" "libhwloc-dev")
endif()
pkg_check_modules(CYAML QUIET IMPORTED_TARGET GLOBAL libcyaml>=1.1)
if(NOT CYAML_FOUND)
  _pdk_missing("libcyaml" "libcyaml-dev")
endif()

set(HDF5_PREFER_PARALLEL FALSE)
find_package(HDF5 QUIET COMPONENTS C)
if(NOT HDF5_FOUND)
  _pdk_missing("HDF5 (C API)" "libhdf5-dev")
endif()

find_package(SuiteSparsePdk QUIET)
if(NOT SuiteSparsePdk_FOUND)
  _pdk_missing("SuiteSparse (CHOLMOD, UMFPACK)" "libsuitesparse-dev")
endif()

find_library(PDK_LIBM m)

# An optimized BLAS for CHOLMOD's supernodal factorization (optional). CHOLMOD calls the BLAS
# through libblas.so.3, which Debian's alternatives point at OpenBLAS once libopenblas-dev is
# installed (the README's first command installs it), so nothing links differently. Without it
# the reference (netlib) BLAS factors the Newton tangents several times slower (measured in
# bench/README.md, "Static solvers").
find_library(PDK_OPENBLAS NAMES openblas)
if(NOT PDK_OPENBLAS)
  message(STATUS "pdk: OpenBLAS not found: CHOLMOD will run on the reference BLAS (Newton "
                 "factorizations several times slower). Install it with:\n"
                 "  apt-get install -y libopenblas-dev")
endif()
