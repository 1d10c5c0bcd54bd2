# `pdk run` of a Johnson-Cook scene whose loads the law cannot follow stops with a message and
# exit 1 instead of finishing with zero stresses: scenes/plate_two_holes.yaml at 1 mm with its grip
# at 1e20 m/s. Before, the run went to the end (exit 0) and its energy summary read "off by 0 (0%
# of the energy put in)"; now the first step stops naming the step, the particle (index and id),
# why and what to check, and no energy summary or "done" line is printed (the account of a run
# that failed is not given).
# labels: unit
cmake_minimum_required(VERSION 3.25)
file(REMOVE_RECURSE ${PDK_TEST_DIR})
file(MAKE_DIRECTORY ${PDK_TEST_DIR})
execute_process(COMMAND ${PDK_CLI} run ${PDK_SOURCE_DIR}/scenes/plate_two_holes.yaml -q -o out
                        --set geometry.spacing=1e-3 --set boundary_conditions[1].y=1e20
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                WORKING_DIRECTORY ${PDK_TEST_DIR})
if(NOT rc EQUAL 1)
  message(FATAL_ERROR "exit ${rc}, expected 1\n${out}${err}")
endif()
if(NOT err MATCHES "pdk: step 1 \\(time [0-9.e+-]+\\): the Johnson-Cook update failed for particle [0-9]+ \\(id [0-9]+, now at"
   OR NOT err MATCHES "take smaller steps or check the boundary conditions' values")
  message(FATAL_ERROR "no message naming the step, the particle and the remedy:\n${err}")
endif()
if(err MATCHES "energy:" OR err MATCHES "off by" OR err MATCHES "done:")
  message(FATAL_ERROR "a failed run printed its summary:\n${err}")
endif()
