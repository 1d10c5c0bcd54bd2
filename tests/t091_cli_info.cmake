# The pdk command: `pdk info` reports version, build flags, SIMD, topology and binding; help for
# every subcommand; bad arguments give a message and a non-zero exit.
# labels: unit
cmake_minimum_required(VERSION 3.25)

function(expect rc_want out_regex)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc_want STREQUAL "0" AND NOT rc EQUAL 0)
    message(FATAL_ERROR "${ARGN}: exit ${rc}, expected 0\n${out}${err}")
  elseif(NOT rc_want STREQUAL "0" AND rc EQUAL 0)
    message(FATAL_ERROR "${ARGN}: exit 0, expected failure\n${out}${err}")
  endif()
  if(NOT "${out}${err}" MATCHES "${out_regex}")
    message(FATAL_ERROR "${ARGN}: output does not match '${out_regex}':\n${out}${err}")
  endif()
endfunction()

file(READ ${PDK_BUILD_DIR}/include/pdk/version.h vh)
string(REGEX MATCH "PDK_VERSION_STRING \"([^\"]+)\"" _ "${vh}")
set(version ${CMAKE_MATCH_1})

expect(0 "pdk ${version}\nbuild: [A-Za-z]+, .*flags: .*SIMD \\(run time\\): avx2\\+fma (yes|no), avx512 (yes|no).*topology \\(hwloc\\): [0-9]+ package\\(s\\), [0-9]+ core\\(s\\).*NUMA node.*threads: [0-9]+ .*thread 0: " ${PDK_CLI} info)
expect(0 "threads: 1 .*thread 0: PUs" ${PDK_CLI} info --threads 1)
expect(0 "binding policy: none" ${CMAKE_COMMAND} -E env PDK_BIND=none ${PDK_CLI} info)
expect(0 "usage: pdk <command>" ${PDK_CLI} --help)
expect(0 "usage: pdk info" ${PDK_CLI} info --help)
expect(0 "pdk ${version}" ${PDK_CLI} --version)
expect(2 "unknown command 'frobnicate'" ${PDK_CLI} frobnicate)
expect(2 "--threads '0' is not a thread count" ${PDK_CLI} info --threads 0)
expect(2 "unknown option '--fast'" ${PDK_CLI} info --fast)
expect(1 "PDK_BIND='socket' is not a binding policy" ${CMAKE_COMMAND} -E env PDK_BIND=socket ${PDK_CLI} info)
expect(1 "PDK_KERNELS/kernels='avx9'" ${CMAKE_COMMAND} -E env PDK_KERNELS=avx9 ${PDK_CLI} info)
