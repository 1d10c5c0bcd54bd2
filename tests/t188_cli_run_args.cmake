# `pdk run` refuses output folders and checkpoints it cannot use, with one clear line and exit 2:
#   - -o '' (an empty folder name), and an -o longer than the system's path limit (not cut short);
#     nothing is created;
#   - --restart of a file that is not a checkpoint (a YAML scene, a missing file, a folder, the
#     run's own output .h5): one line on stderr that names the file, no HDF5 error stack
#     (no "HDF5-DIAG", no H5F... call names), before the scene is built.
# labels: unit
cmake_minimum_required(VERSION 3.25)
set(scene ${PDK_SOURCE_DIR}/tests/scenes/t092_bar.yaml)
file(REMOVE_RECURSE ${PDK_TEST_DIR})
file(MAKE_DIRECTORY ${PDK_TEST_DIR})

# The command's exit status must be 2 and its stderr one line that matches `pattern`.
function(check_refused what rc err pattern)
  if(NOT rc STREQUAL "2")
    message(FATAL_ERROR "${what}: exit ${rc}, expected 2\n${err}")
  endif()
  string(REGEX MATCHALL "\n" newlines "${err}")
  list(LENGTH newlines num_lines)
  if(NOT num_lines EQUAL 1 OR NOT err MATCHES "${pattern}")
    message(FATAL_ERROR "${what}: expected one line matching '${pattern}', got:\n${err}")
  endif()
  if(err MATCHES "HDF5-DIAG|H5F[a-z_]*\\(|H5D[a-z_]*\\(|HDF5 call")
    message(FATAL_ERROR "${what}: an HDF5 error stack on stderr:\n${err}")
  endif()
endfunction()

function(refused pattern)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err
                  WORKING_DIRECTORY ${PDK_TEST_DIR})
  check_refused("${ARGN}" "${rc}" "${err}" "${pattern}")
endfunction()

# (an empty argument does not survive ${ARGN}: this one is spelled out)
execute_process(COMMAND ${PDK_CLI} run ${scene} -o "" RESULT_VARIABLE rc OUTPUT_QUIET
                ERROR_VARIABLE err WORKING_DIRECTORY ${PDK_TEST_DIR})
check_refused("-o ''" "${rc}" "${err}" "^pdk: -o: the output folder is empty")
string(REPEAT "x" 5000 long)
refused("^pdk: -o: the output folder 'x+[.][.][.]x+' is 5000 bytes long.*PATH_MAX"
        ${PDK_CLI} run ${scene} -o ${long})
file(GLOB made ${PDK_TEST_DIR}/*)
if(made)
  message(FATAL_ERROR "a refused -o created ${made}")
endif()

refused("^pdk: --restart: '[^']*t092_bar.yaml' is not a pdk checkpoint: it is not an HDF5 file"
        ${PDK_CLI} run ${scene} -o out --restart ${scene})
refused("^pdk: --restart: checkpoint 'no_such.h5' does not exist"
        ${PDK_CLI} run ${scene} -o out --restart no_such.h5)
file(MAKE_DIRECTORY ${PDK_TEST_DIR}/folder.h5)
refused("^pdk: --restart: 'folder.h5' is a folder, not a checkpoint"
        ${PDK_CLI} run ${scene} -o out --restart folder.h5)
execute_process(COMMAND ${PDK_CLI} run ${scene} -o out -q --set solver.steps=10
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                WORKING_DIRECTORY ${PDK_TEST_DIR})
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the run whose output the next case restarts from failed (exit ${rc}):\n"
                      "${out}${err}")
endif()
refused("^pdk: --restart: 'out/bar.h5' is a 'pdk output' file, not a pdk checkpoint"
        ${PDK_CLI} run ${scene} -o out --restart out/bar.h5)
