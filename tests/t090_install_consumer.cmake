# Installs pdk into a scratch prefix, then builds and runs a small consumer program against the
# installed tree twice: with find_package(pdk) (pdk::pdk and pdk::pdk_static) and with pkg-config.
# labels: install
cmake_minimum_required(VERSION 3.25)
set(prefix ${PDK_TEST_DIR}/prefix)
file(REMOVE_RECURSE ${PDK_TEST_DIR})
file(MAKE_DIRECTORY ${PDK_TEST_DIR}/consumer)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "command failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(run_out "${out}" PARENT_SCOPE)
endfunction()

run(${CMAKE_COMMAND} --install ${PDK_BUILD_DIR} --prefix ${prefix})
foreach(f include/pdk/pdk.h include/pdk/version.h lib/libpdk.a lib/pkgconfig/pdk.pc
          lib/cmake/pdk/pdkConfig.cmake bin/pdk)
  if(NOT EXISTS ${prefix}/${f})
    # Debian's GNUInstallDirs may use lib/<multiarch>; look there too.
    file(GLOB alt ${prefix}/lib/*/${f})
    string(REPLACE "lib/" "" tail "${f}")
    file(GLOB alt ${prefix}/lib/*/${tail})
    if(NOT alt)
      message(FATAL_ERROR "install did not create ${f}")
    endif()
  endif()
endforeach()

file(WRITE ${PDK_TEST_DIR}/consumer/main.c [=[
#include <pdk/pdk.h>
#include <stdio.h>
#include <string.h>
int main(void) {
  pdk_ctx *ctx = NULL;
  char why[256];
  if (pdk_ctx_create(NULL, &ctx, why, sizeof why)) { fprintf(stderr, "%s\n", why); return 1; }
  pdk_particles *p = NULL;
  if (pdk_particles_create(ctx, 3, 10, &p)) { fprintf(stderr, "%s\n", pdk_ctx_error_message(ctx)); return 1; }
  int ok = pdk_particles_count(p) == 10 && strcmp(PDK_VERSION_STRING, "") != 0;
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
  printf("consumer ok %s\n", PDK_VERSION_STRING);
  return ok ? 0 : 1;
}
]=])
file(WRITE ${PDK_TEST_DIR}/consumer/CMakeLists.txt [=[
cmake_minimum_required(VERSION 3.25)
project(consumer C)
find_package(pdk REQUIRED)
add_executable(consumer_shared main.c)
target_link_libraries(consumer_shared PRIVATE pdk::pdk)
add_executable(consumer_static main.c)
target_link_libraries(consumer_static PRIVATE pdk::pdk_static)
]=])
run(${CMAKE_COMMAND} -S ${PDK_TEST_DIR}/consumer -B ${PDK_TEST_DIR}/consumer/build
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_C_COMPILER=${CMAKE_C_COMPILER})
run(${CMAKE_COMMAND} --build ${PDK_TEST_DIR}/consumer/build)
foreach(exe consumer_shared consumer_static)
  run(${PDK_TEST_DIR}/consumer/build/${exe})
  if(NOT run_out MATCHES "consumer ok")
    message(FATAL_ERROR "${exe} printed: ${run_out}")
  endif()
endforeach()

# pkg-config (shared library; the static archive is covered by pdk::pdk_static above, since
# `pkg-config --static` would pull hwloc's private -ludev, which Debian ships only in libudev-dev).
file(GLOB_RECURSE pcfile ${prefix}/pdk.pc)
get_filename_component(pcdir ${pcfile} DIRECTORY)
set(ENV{PKG_CONFIG_PATH} ${pcdir})
run(pkg-config --cflags --libs pdk)
string(STRIP "${run_out}" flags)
separate_arguments(flags UNIX_COMMAND "${flags}")
get_filename_component(libdir ${pcdir} DIRECTORY)
run(${CMAKE_C_COMPILER} ${PDK_TEST_DIR}/consumer/main.c ${flags} -Wl,-rpath,${libdir}
    -o ${PDK_TEST_DIR}/consumer/pc_shared)
run(${PDK_TEST_DIR}/consumer/pc_shared)
if(DEFINED ENV{PDK_TEST_VERBOSE})
  message(STATUS "installed tree works with find_package(pdk) and pkg-config")
endif()
