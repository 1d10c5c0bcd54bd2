# What an installed pdk must do, whatever its prefix and library folder (included by t090, an
# /opt-like prefix from the build under test, and t231, a /usr-like prefix with the multiarch
# library folder): pdk_check_installed(PREFIX WORK) checks, in the tree installed at PREFIX,
# - the installed `pdk` runs without LD_LIBRARY_PATH (it finds libpdk.so by its relative RPATH)
#   and checks an installed scene (share/pdk/scenes); docs, LICENSE and examples are installed;
# - a consumer program builds and runs with find_package(pdk) (pdk::pdk and pdk::pdk_static);
# - with pkg-config: the shared library, and `pkg-config --static` against libpdk.a (when
#   hwloc's private -ludev can be linked: Debian's libudev-dev);
# - the installed examples build with find_package(pdk) and one runs.
# WORK is a scratch folder. Needs run() (tests/script_run.cmake) and CMAKE_C_COMPILER.

function(pdk_check_installed prefix work)
  file(MAKE_DIRECTORY ${work}/consumer)
  # the library folder: lib, lib64 or lib/<multiarch>
  file(GLOB_RECURSE pcfile ${prefix}/*/pdk.pc)
  if(NOT pcfile)
    message(FATAL_ERROR "no pdk.pc under ${prefix}")
  endif()
  get_filename_component(pcdir ${pcfile} DIRECTORY)
  get_filename_component(libdir ${pcdir} DIRECTORY)
  foreach(f include/pdk/pdk.h include/pdk/version.h bin/pdk share/pdk/scenes/bar_tension.yaml
          share/doc/pdk/README.md share/doc/pdk/LICENSE share/doc/pdk/scenes.md
          share/doc/pdk/examples/CMakeLists.txt)
    if(NOT EXISTS ${prefix}/${f})
      message(FATAL_ERROR "install did not create ${prefix}/${f}")
    endif()
  endforeach()
  foreach(f libpdk.a libpdk.so cmake/pdk/pdkConfig.cmake)
    if(NOT EXISTS ${libdir}/${f})
      message(FATAL_ERROR "install did not create ${libdir}/${f}")
    endif()
  endforeach()

  # The installed program, with no library path set.
  set(ENV{LD_LIBRARY_PATH} "")
  run(${prefix}/bin/pdk check ${prefix}/share/pdk/scenes/bar_tension.yaml)
  if(NOT run_out MATCHES "bar_tension")
    message(FATAL_ERROR "installed pdk check printed: ${run_out}")
  endif()

  file(WRITE ${work}/consumer/main.c [=[
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
  file(WRITE ${work}/consumer/CMakeLists.txt [=[
cmake_minimum_required(VERSION 3.25)
project(consumer C)
find_package(pdk REQUIRED)
add_executable(consumer_shared main.c)
target_link_libraries(consumer_shared PRIVATE pdk::pdk)
add_executable(consumer_static main.c)
target_link_libraries(consumer_static PRIVATE pdk::pdk_static)
]=])
  run(${CMAKE_COMMAND} -S ${work}/consumer -B ${work}/consumer/build
      -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_C_COMPILER=${CMAKE_C_COMPILER})
  run(${CMAKE_COMMAND} --build ${work}/consumer/build)
  foreach(exe consumer_shared consumer_static)
    run(${work}/consumer/build/${exe})
    if(NOT run_out MATCHES "consumer ok")
      message(FATAL_ERROR "${exe} printed: ${run_out}")
    endif()
  endforeach()

  # pkg-config: the flags must point into this prefix, whatever its library folder.
  set(ENV{PKG_CONFIG_PATH} ${pcdir})
  run(pkg-config --cflags --libs pdk)
  string(STRIP "${run_out}" flags)
  file(REAL_PATH ${prefix}/include incdir)
  separate_arguments(flags UNIX_COMMAND "${flags}")
  set(found_inc 0)
  foreach(fl ${flags})
    if(fl MATCHES "^-I(.*)")
      file(REAL_PATH "${CMAKE_MATCH_1}" got)
      if(got STREQUAL incdir)
        set(found_inc 1)
      endif()
    endif()
  endforeach()
  if(NOT found_inc)
    message(FATAL_ERROR "pkg-config --cflags gives ${flags}, not -I${prefix}/include")
  endif()
  run(${CMAKE_C_COMPILER} ${work}/consumer/main.c ${flags} -Wl,-rpath,${libdir}
      -o ${work}/consumer/pc_shared)
  run(${work}/consumer/pc_shared)
  find_library(udev_lib udev)
  if(udev_lib)
    run(pkg-config --static --cflags --libs pdk)
    string(STRIP "${run_out}" flags)
    separate_arguments(flags UNIX_COMMAND "${flags}")
    list(TRANSFORM flags REPLACE "^-lpdk$" "${libdir}/libpdk.a")
    run(${CMAKE_C_COMPILER} ${work}/consumer/main.c ${flags} -o ${work}/consumer/pc_static)
    run(${work}/consumer/pc_static)
    if(NOT run_out MATCHES "consumer ok")
      message(FATAL_ERROR "pc_static printed: ${run_out}")
    endif()
  elseif(DEFINED ENV{PDK_TEST_VERBOSE})
    message(STATUS "no libudev: pkg-config --static not tried (apt-get install libudev-dev)")
  endif()

  # The installed examples, built against the installed tree.
  run(${CMAKE_COMMAND} -S ${prefix}/share/doc/pdk/examples -B ${work}/examples
      -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_C_COMPILER=${CMAKE_C_COMPILER})
  run(${CMAKE_COMMAND} --build ${work}/examples)
  run(${work}/examples/example_lattice_forces 8)
  if(NOT run_out MATCHES "energy per volume")
    message(FATAL_ERROR "the installed example printed: ${run_out}")
  endif()
endfunction()
