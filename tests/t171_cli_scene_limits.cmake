# The pdk command refuses input over the scene limits before doing the work (docs/scenes.md,
# "Limits"): `pdk check /dev/zero` exits 2 at once with a message naming the 8 MiB limit (without
# the limit it reads until the kernel kills it); a scene whose memory estimate is beyond any
# machine (1.6e9 points, about 1.4 TB) exits 2 from `pdk check` and `pdk run`, naming the estimate
# and limits.memory, and `pdk run` leaves no output directory; a scene without `name:` whose file
# stem cannot name files exits 2 asking for `name:`.
# labels: unit
cmake_minimum_required(VERSION 3.25)
set(scene ${PDK_SOURCE_DIR}/tests/scenes/t092_bar.yaml)
file(REMOVE_RECURSE ${PDK_TEST_DIR})
file(MAKE_DIRECTORY ${PDK_TEST_DIR})

function(run expect_rc)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  WORKING_DIRECTORY ${PDK_TEST_DIR} TIMEOUT 60)
  if(NOT rc STREQUAL "${expect_rc}")
    message(FATAL_ERROR "${ARGN}: exit ${rc}, expected ${expect_rc}\n${out}${err}")
  endif()
  set(run_out "${out}${err}" PARENT_SCOPE)
endfunction()

if(EXISTS /dev/zero)
  run(2 ${PDK_CLI} check /dev/zero)
  if(NOT run_out MATCHES "/dev/zero: more than 8 MiB were read.*the limit for scene files")
    message(FATAL_ERROR "pdk check /dev/zero: ${run_out}")
  endif()
endif()

set(huge --set "geometry.box.hi=[1, 1]" --set geometry.spacing=2.5e-5)
run(2 ${PDK_CLI} check ${scene} ${huge})
if(NOT run_out MATCHES "geometry.spacing: the run needs about [0-9.]+ TB by pdk's estimate .*limits.memory")
  message(FATAL_ERROR "pdk check of a 1.6e9-point scene: ${run_out}")
endif()
run(2 ${PDK_CLI} run ${scene} ${huge} -o huge)
if(NOT run_out MATCHES "limits.memory" OR EXISTS ${PDK_TEST_DIR}/huge)
  message(FATAL_ERROR "pdk run of a 1.6e9-point scene: ${run_out}")
endif()

# a stem that is not a name: the message asks for name:, and --set name=... runs
file(READ ${scene} text)
string(REGEX REPLACE "\nname: bar\n" "\n" text "${text}")
file(WRITE "${PDK_TEST_DIR}/-bar.yaml" "${text}")
run(2 ${PDK_CLI} check ./-bar.yaml)
if(NOT run_out MATCHES "-bar.yaml:1: name: .*set name:")
  message(FATAL_ERROR "pdk check ./-bar.yaml: ${run_out}")
endif()
run(0 ${PDK_CLI} check ./-bar.yaml --set name=bar)
