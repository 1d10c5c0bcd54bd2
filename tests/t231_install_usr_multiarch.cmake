# A /usr-like install: configures pdk (library and program only) with CMAKE_INSTALL_PREFIX=/usr,
# where GNUInstallDirs picks the multiarch library folder on Debian (lib/x86_64-linux-gnu), builds
# it, installs it into a staging folder (DESTDIR, as a package build does) and checks the staged
# tree with tests/install_checks.cmake: pdk.pc and the CMake package must resolve to the staged
# include and library folders (not <prefix>/lib/include or lib/lib/<multiarch>), the installed
# pdk must find libpdk.so through its relative RPATH. Builds the library a second time (about
# 2.5 CPU-minutes).
# labels: install
cmake_minimum_required(VERSION 3.25)
file(REMOVE_RECURSE ${PDK_TEST_DIR})
file(MAKE_DIRECTORY ${PDK_TEST_DIR})

include(${CMAKE_CURRENT_LIST_DIR}/script_run.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/install_checks.cmake)

set(build ${PDK_TEST_DIR}/build)
run(${CMAKE_COMMAND} -S ${PDK_SOURCE_DIR} -B ${build} -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_INSTALL_PREFIX=/usr -DCMAKE_C_COMPILER=${CMAKE_C_COMPILER} -DPDK_BUILD_TESTS=OFF
    -DPDK_BUILD_BENCH=OFF -DPDK_BUILD_EXAMPLES=OFF -DPDK_SANITIZE=${PDK_SANITIZE})
run(${CMAKE_COMMAND} --build ${build} -j2)
set(ENV{DESTDIR} ${PDK_TEST_DIR}/stage)
run(${CMAKE_COMMAND} --install ${build})
unset(ENV{DESTDIR})
pdk_check_installed(${PDK_TEST_DIR}/stage/usr ${PDK_TEST_DIR}/work)
