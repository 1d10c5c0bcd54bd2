# `pdk run --restart`: the checkpoint's time, step and dt are the run's, and it ends where the
# scene says.
#   - the same scene (solver.end_time, a fixed dt) run to half its end and restarted to the end
#     ends at the uninterrupted run's last step with its last history row bit for bit;
#   - a restart that asks for another dt (--set solver.dt) with solver.end_time says so, steps at
#     the new dt from the checkpoint on and ends at end_time (within one step, not before it);
#   - another dt with solver.steps is refused (exit 2) naming solver.dt, as the same step count
#     would end the run at another time; so is an end_time before the checkpoint, naming
#     solver.end_time; neither touches the output.
# labels: unit
cmake_minimum_required(VERSION 3.25)
file(REMOVE_RECURSE ${PDK_TEST_DIR})
file(MAKE_DIRECTORY ${PDK_TEST_DIR})
# the bar of t092 run to an end time at a fixed step
file(READ ${PDK_SOURCE_DIR}/tests/scenes/t092_bar.yaml bar)
string(REPLACE "solver: {steps: 400}" "solver: {end_time: 3.0e-4, dt: 2.0e-6}" bar_t "${bar}")
if(bar_t STREQUAL bar)
  message(FATAL_ERROR "t092_bar.yaml no longer says 'solver: {steps: 400}'")
endif()
file(WRITE ${PDK_TEST_DIR}/bar_t.yaml "${bar_t}")
set(scene ${PDK_TEST_DIR}/bar_t.yaml)

function(run expect_rc)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  WORKING_DIRECTORY ${PDK_TEST_DIR})
  if(NOT rc STREQUAL "${expect_rc}")
    message(FATAL_ERROR "${ARGN}: exit ${rc}, expected ${expect_rc}\n${out}${err}")
  endif()
  set(run_out "${out}${err}" PARENT_SCOPE)
endfunction()

function(last_row csv var)
  file(STRINGS ${csv} rows)
  list(GET rows -1 row)
  set(${var} "${row}" PARENT_SCOPE)
endfunction()

# uninterrupted: 150 steps of 2e-6 to 3e-4
run(0 ${PDK_CLI} run ${scene} -o full -q)
last_row(${PDK_TEST_DIR}/full/bar_history.csv full_row)
if(NOT full_row MATCHES "^150,")
  message(FATAL_ERROR "the uninterrupted run does not end at step 150: ${full_row}")
endif()

# half (to 1.5e-4), then the same scene from its checkpoint: the same end, bit for bit
run(0 ${PDK_CLI} run ${scene} -o half -q --set solver.end_time=1.5e-4)
run(0 ${PDK_CLI} run ${scene} -o half -q --restart half/bar_checkpoint.h5)
last_row(${PDK_TEST_DIR}/half/bar_history.csv half_row)
if(NOT half_row STREQUAL full_row)
  message(FATAL_ERROR "restarted to the scene's end_time:\n  ${half_row}\nuninterrupted:\n  ${full_row}")
endif()

# another dt with end_time: said, and the run ends at 3e-4 at the new step, 75 + 150 steps
run(0 ${PDK_CLI} run ${scene} -o dt -q --set solver.end_time=1.5e-4)
run(0 ${PDK_CLI} run ${scene} -o dt -q --set solver.dt=1e-6 --restart dt/bar_checkpoint.h5)
if(NOT run_out MATCHES "solver.dt: the restart steps at 1e-06 from the checkpoint \\(step 75")
  message(FATAL_ERROR "no message that the step changed:\n${run_out}")
endif()
file(STRINGS ${PDK_TEST_DIR}/dt/bar_history.csv dt_rows)
list(GET dt_rows 0 header)
list(GET dt_rows -1 dt_row)
include(${CMAKE_CURRENT_LIST_DIR}/csv_column.cmake)
csv_column("${header}" "^dt \\[[a-z]+\\]$" dt_col)
string(REPLACE "," ";" values "${dt_row}")
list(GET values 0 last_step)
list(GET values 1 last_time)
list(GET values ${dt_col} last_dt)
# the last step ends at or after 3e-4 and starts before it (t - dt < 3e-4)
execute_process(COMMAND awk "BEGIN { t = ${last_time}; d = ${last_dt}; exit !(t >= 3e-4 * (1 - 1e-12) && t - d < 3e-4 && d == 1e-6) }"
                RESULT_VARIABLE at_end)
if(NOT last_step EQUAL 225 OR NOT at_end EQUAL 0)
  message(FATAL_ERROR "the restart at dt 1e-6 ends at step ${last_step}, t = ${last_time}, dt = "
                      "${last_dt}; expected step 225 at t = 3e-4 with dt 1e-6")
endif()

# another dt with solver.steps: refused, naming solver.dt; the output stays
run(0 ${PDK_CLI} run ${PDK_SOURCE_DIR}/tests/scenes/t092_bar.yaml -o steps -q --set solver.steps=200)
file(READ ${PDK_TEST_DIR}/steps/bar_history.csv steps_before)
run(2 ${PDK_CLI} run ${PDK_SOURCE_DIR}/tests/scenes/t092_bar.yaml -o steps -q --set solver.dt=1e-6
    --restart steps/bar_checkpoint.h5)
if(NOT run_out MATCHES "solver.dt: the scene steps at 1e-06.*solver.steps.*solver.end_time")
  message(FATAL_ERROR "another dt with solver.steps: ${run_out}")
endif()
file(READ ${PDK_TEST_DIR}/steps/bar_history.csv steps_after)
if(NOT steps_after STREQUAL steps_before)
  message(FATAL_ERROR "a refused restart changed the output")
endif()

# an end_time before the checkpoint: refused, naming solver.end_time
run(2 ${PDK_CLI} run ${scene} -o half -q --set solver.end_time=1e-4 --restart half/bar_checkpoint.h5)
if(NOT run_out MATCHES "solver.end_time: 0.0001 ends before the time of checkpoint")
  message(FATAL_ERROR "an end before the checkpoint: ${run_out}")
endif()
