# Installs the build under test into an /opt-like scratch prefix (lib/, or the library folder the
# build was configured with) and checks the installed tree (tests/install_checks.cmake: the
# installed pdk runs without a library path, scenes, docs and examples are there, consumers build
# with find_package(pdk) and with pkg-config, shared and static); then moves the tree elsewhere and
# checks that the installed pdk and pdk.pc still work (both find their folders relative to
# themselves). t231 does the same for a /usr-like prefix with the multiarch library folder.
# labels: install
cmake_minimum_required(VERSION 3.25)
set(prefix ${PDK_TEST_DIR}/opt/pdk)
file(REMOVE_RECURSE ${PDK_TEST_DIR})
file(MAKE_DIRECTORY ${PDK_TEST_DIR})

include(${CMAKE_CURRENT_LIST_DIR}/script_run.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/install_checks.cmake)

run(${CMAKE_COMMAND} --install ${PDK_BUILD_DIR} --prefix ${prefix})
pdk_check_installed(${prefix} ${PDK_TEST_DIR}/work)

# Moved: the program and pkg-config follow.
set(moved ${PDK_TEST_DIR}/elsewhere/pdk)
file(MAKE_DIRECTORY ${PDK_TEST_DIR}/elsewhere)
file(RENAME ${prefix} ${moved})
run(${moved}/bin/pdk check ${moved}/share/pdk/scenes/bar_tension.yaml)
file(GLOB_RECURSE pcfile ${moved}/*/pdk.pc)
get_filename_component(pcdir ${pcfile} DIRECTORY)
set(ENV{PKG_CONFIG_PATH} ${pcdir})
run(pkg-config --variable=includedir pdk)
string(STRIP "${run_out}" inc)
if(NOT EXISTS ${inc}/pdk/pdk.h)
  message(FATAL_ERROR "pkg-config's includedir ${inc} of the moved tree has no pdk/pdk.h")
endif()
if(DEFINED ENV{PDK_TEST_VERBOSE})
  message(STATUS "installed tree works at ${prefix} and moved to ${moved}")
endif()
