# Finds CHOLMOD and UMFPACK from SuiteSparse (Debian's libsuitesparse-dev ships neither a CMake
# config nor pkg-config files before SuiteSparse 7) and defines SuiteSparsePdk::SuiteSparsePdk.
include(FindPackageHandleStandardArgs)
find_path(SuiteSparsePdk_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
find_library(SuiteSparsePdk_CHOLMOD cholmod)
find_library(SuiteSparsePdk_UMFPACK umfpack)
find_library(SuiteSparsePdk_CONFIG suitesparseconfig)
find_library(SuiteSparsePdk_AMD amd)
find_library(SuiteSparsePdk_COLAMD colamd)
find_package_handle_standard_args(SuiteSparsePdk REQUIRED_VARS SuiteSparsePdk_INCLUDE_DIR
  SuiteSparsePdk_CHOLMOD SuiteSparsePdk_UMFPACK SuiteSparsePdk_CONFIG SuiteSparsePdk_AMD
  SuiteSparsePdk_COLAMD)
if(SuiteSparsePdk_FOUND AND NOT TARGET SuiteSparsePdk::SuiteSparsePdk)
  add_library(SuiteSparsePdk::SuiteSparsePdk INTERFACE IMPORTED)
  set_target_properties(SuiteSparsePdk::SuiteSparsePdk PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparsePdk_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${SuiteSparsePdk_UMFPACK};${SuiteSparsePdk_CHOLMOD};${SuiteSparsePdk_AMD};${SuiteSparsePdk_COLAMD};${SuiteSparsePdk_CONFIG}")
endif()
