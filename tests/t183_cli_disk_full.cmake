# `pdk run` onto a full disk and onto a read-only one: a message naming the file and the reason,
# exit status 1 (never a crash: HDF5 1.10 left a file it could not close, and its exit handler
# died of SIGSEGV, status 139), and no output file left (no .part, no data file; the checkpoint,
# written before the output is closed, may stay: it is complete). The disks are tmpfs mounts of
# 16 kB to 256 kB under the test's folder (the run's files take about 540 kB), which needs root:
# without the right to mount, the test prints why and is reported as skipped.
# labels: unit
cmake_minimum_required(VERSION 3.25)
set(scene ${PDK_SOURCE_DIR}/tests/scenes/t092_bar.yaml)
set(mnt ${PDK_TEST_DIR}/disk)
execute_process(COMMAND umount ${mnt} RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
file(REMOVE_RECURSE ${PDK_TEST_DIR})
file(MAKE_DIRECTORY ${mnt})

execute_process(COMMAND mount -t tmpfs -o size=16k tmpfs ${mnt} RESULT_VARIABLE rc
                ERROR_VARIABLE why OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message("pdk-test-skip: cannot mount a tmpfs at ${mnt} (mount: ${rc} ${why}); the test needs root")
  return()
endif()

function(fail msg)
  execute_process(COMMAND umount ${mnt} OUTPUT_QUIET ERROR_QUIET)
  message(FATAL_ERROR "${msg}")
endfunction()

# Runs the scene into the mount; checks the status, the message and what is left.
function(run_into label expect_rc expect_msg)
  execute_process(COMMAND ${PDK_CLI} run ${scene} -o ${mnt}/out -q RESULT_VARIABLE rc
                  OUTPUT_VARIABLE out ERROR_VARIABLE err)
  file(GLOB left RELATIVE ${mnt}/out ${mnt}/out/*)
  if(NOT rc STREQUAL "${expect_rc}")
    fail("${label}: exit ${rc}, expected ${expect_rc}\n${out}${err}\nleft: ${left}")
  endif()
  if(NOT err MATCHES "${expect_msg}")
    fail("${label}: the message does not say '${expect_msg}':\n${err}")
  endif()
  if(expect_rc EQUAL 0)
    return()
  endif()
  if(NOT err MATCHES "pdk: cannot (write|create) '${mnt}/out/bar[^']*'")
    fail("${label}: the message does not name the file:\n${err}")
  endif()
  list(REMOVE_ITEM left bar_checkpoint.h5)
  if(left)
    fail("${label}: files left after the failure: ${left}\n${err}")
  endif()
endfunction()

foreach(size 16k 64k 256k)
  execute_process(COMMAND umount ${mnt})
  execute_process(COMMAND mount -t tmpfs -o size=${size} tmpfs ${mnt} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    fail("cannot mount a ${size} tmpfs")
  endif()
  run_into("a ${size} disk" 1 "No space left on device")
endforeach()

# read-only: the output folder exists, nothing can be created in it
execute_process(COMMAND umount ${mnt})
execute_process(COMMAND mount -t tmpfs -o size=1m tmpfs ${mnt})
file(MAKE_DIRECTORY ${mnt}/out)
execute_process(COMMAND mount -o remount,ro ${mnt} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  fail("cannot remount ${mnt} read-only")
endif()
run_into("a read-only disk" 1 "Read-only file system")

# the same run with room enough succeeds (the checks above are not the scene's own failure)
execute_process(COMMAND umount ${mnt})
execute_process(COMMAND mount -t tmpfs -o size=2m tmpfs ${mnt})
run_into("a 2 MB disk" 0 "")
if(NOT EXISTS ${mnt}/out/bar.xmf OR NOT EXISTS ${mnt}/out/bar.h5)
  fail("a 2 MB disk: no complete output")
endif()
execute_process(COMMAND umount ${mnt})
