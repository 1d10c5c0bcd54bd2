# The pdk command end to end: `pdk run` writes the HDF5, XDMF, CSVs and checkpoint (no .part file
# left; in 2-D the last field output as CSV), `pdk check` validates without writing, a restarted run ends bitwise where an uninterrupted
# one ends, Ctrl-C stops cleanly with a checkpoint and exit 130, bad scenes and overrides exit 2
# with file:line:key messages; progress lines go to a log when stderr is not a terminal.
# labels: unit
cmake_minimum_required(VERSION 3.25)
set(scene ${PDK_SOURCE_DIR}/tests/scenes/t092_bar.yaml)
file(REMOVE_RECURSE ${PDK_TEST_DIR})
file(MAKE_DIRECTORY ${PDK_TEST_DIR})

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

# check: valid scene, nothing written
run(0 ${PDK_CLI} check ${scene})
if(NOT run_out MATCHES "ok: .*t092_bar.yaml is valid" OR NOT run_out MATCHES "particles")
  message(FATAL_ERROR "check output: ${run_out}")
endif()
file(GLOB written ${PDK_TEST_DIR}/*)
if(written)
  message(FATAL_ERROR "pdk check wrote files: ${written}")
endif()

# progress when stderr is not a terminal (here: captured): whole lines at least every 10% of the
# steps and PDK_PROGRESS_SECONDS (0: no wall-time floor), so between 5 and 10 of them, in order;
# none with -q; none while the wall-time floor has not passed (1e9 s here: the default, 10 s,
# keeps a short run's log free of them, but how long this run takes depends on the machine's load,
# so the default is not what is asserted)
set(ENV{PDK_PROGRESS_SECONDS} 0)
run(0 ${PDK_CLI} run ${scene} -o progress)
string(REGEX MATCHALL "\nstep [0-9]+/[0-9]+ [(][0-9]+%[)]  t [0-9.e+-]+  wall [^\n]*ETA [^\n]*broken [0-9]+  E [^\n]*" lines "${run_out}")
list(LENGTH lines nlines)
if(nlines LESS 5 OR nlines GREATER 10)
  message(FATAL_ERROR "${nlines} progress lines, expected 5 to 10:\n${run_out}")
endif()
run(0 ${PDK_CLI} run ${scene} -o progress_q -q)
if(run_out MATCHES "\nstep [0-9]+/")
  message(FATAL_ERROR "progress lines with -q:\n${run_out}")
endif()
set(ENV{PDK_PROGRESS_SECONDS} 1e9)
run(0 ${PDK_CLI} run ${scene} -o progress_floor)
if(run_out MATCHES "\nstep [0-9]+/")
  message(FATAL_ERROR "progress lines before the 1e9 s floor has passed:\n${run_out}")
endif()
unset(ENV{PDK_PROGRESS_SECONDS})

# run: all files, no .part left
run(0 ${PDK_CLI} run ${scene} -o full -q)
foreach(f bar.h5 bar.xmf bar_history.csv bar_checkpoint.h5)
  if(NOT EXISTS ${PDK_TEST_DIR}/full/${f})
    message(FATAL_ERROR "pdk run did not write ${f}")
  endif()
endforeach()
file(GLOB parts ${PDK_TEST_DIR}/full/*.part)
if(parts)
  message(FATAL_ERROR "temporary files left: ${parts}")
endif()
last_row(${PDK_TEST_DIR}/full/bar_history.csv full_row)
if(NOT full_row MATCHES "^400,")
  message(FATAL_ERROR "last history row is not step 400: ${full_row}")
endif()
# a 2-D run leaves its last field output as CSV: the header, one row per particle (40 x 6)
file(STRINGS ${PDK_TEST_DIR}/full/bar_fields.csv fields_rows)
list(LENGTH fields_rows fields_len)
list(GET fields_rows 0 fields_header)
if(NOT fields_header STREQUAL "id,X [length],Y [length],u_x,u_y,v_x,v_y" OR
   NOT fields_len EQUAL 241)
  message(FATAL_ERROR "bar_fields.csv: ${fields_len} lines, header '${fields_header}'")
endif()

# restart: half the steps, then continue from its checkpoint to the end: the same last row, bit
# for bit (rows print doubles with 17 significant digits).
run(0 ${PDK_CLI} run ${scene} -o half -q --set solver.steps=200)
run(0 ${PDK_CLI} run ${scene} -o rest -q --restart ${PDK_TEST_DIR}/half/bar_checkpoint.h5)
last_row(${PDK_TEST_DIR}/rest/bar_history.csv rest_row)
if(NOT rest_row STREQUAL full_row)
  message(FATAL_ERROR "restarted run differs:\n  full: ${full_row}\n  rest: ${rest_row}")
endif()
# --threads wins over the scene's solver.threads
run(0 ${PDK_CLI} run ${scene} -o thr --threads 1 --set solver.threads=2 --set solver.steps=10)
if(NOT run_out MATCHES ", 1 thread\\(s\\)")
  message(FATAL_ERROR "--threads 1 not honoured: ${run_out}")
endif()
# output.units labels the files' columns (the bar's scene has none: [length] above)
run(0 ${PDK_CLI} run ${scene} -o si -q --set solver.steps=10 --set output.units=SI)
file(STRINGS ${PDK_TEST_DIR}/si/bar_fields.csv si_fields LIMIT_COUNT 1)
file(STRINGS ${PDK_TEST_DIR}/si/bar_history.csv si_history LIMIT_COUNT 1)
if(NOT si_fields STREQUAL "id,X [m],Y [m],u_x,u_y,v_x,v_y" OR
   NOT si_history MATCHES "^step \\[-\\],time \\[s\\],kinetic \\[J\\],")
  message(FATAL_ERROR "output.units=SI: fields header '${si_fields}', history '${si_history}'")
endif()
# the same with 2 threads on the continuation
run(0 ${PDK_CLI} run ${scene} -o rest2 -q --threads 2 --restart ${PDK_TEST_DIR}/half/bar_checkpoint.h5)
last_row(${PDK_TEST_DIR}/rest2/bar_history.csv rest2_row)
if(NOT rest2_row STREQUAL full_row)
  message(FATAL_ERROR "restarted run on 2 threads differs:\n  full: ${full_row}\n  rest: ${rest2_row}")
endif()

# solver.dt_update lowering the step (tests/scenes/t052_bar_dt.yaml: at step 10): the run says so,
# with the grown step count, and its history ends at that step, at or after end_time.
run(0 ${PDK_CLI} run ${PDK_SOURCE_DIR}/tests/scenes/t052_bar_dt.yaml -o dtu)
if(NOT run_out MATCHES "dt lowered to [0-9.e+-]+ at step 10 .* ([0-9]+) steps in all now")
  message(FATAL_ERROR "dt_update: no 'dt lowered' line:\n${run_out}")
endif()
set(dtu_total ${CMAKE_MATCH_1})
if(NOT run_out MATCHES "done: ${dtu_total} steps" OR NOT run_out MATCHES "dt lowered 1 time")
  message(FATAL_ERROR "dt_update: the run did not end at step ${dtu_total}:\n${run_out}")
endif()
last_row(${PDK_TEST_DIR}/dtu/bar_dt_history.csv dtu_row)
if(NOT dtu_row MATCHES "^${dtu_total},0\\.0002")
  message(FATAL_ERROR
          "dt_update: last history row ${dtu_row}, expected step ${dtu_total} at t >= 2e-4")
endif()
# the history's dt column is the step size: the scene's before step 10, the lowered one (the
# value the run printed, to its 4 digits) from then on
file(STRINGS ${PDK_TEST_DIR}/dtu/bar_dt_history.csv dtu_rows)
list(GET dtu_rows 0 dtu_header)
list(GET dtu_rows 1 dtu_first)
include(${CMAKE_CURRENT_LIST_DIR}/csv_column.cmake)
csv_column("${dtu_header}" "^dt \\[[a-z]+\\]$" dt_col)
if(dt_col LESS 0)
  message(FATAL_ERROR "dt_update: the history has no dt column: ${dtu_header}")
endif()
string(REPLACE "," ";" dtu_first_values "${dtu_first}")
string(REPLACE "," ";" dtu_last_values "${dtu_row}")
list(GET dtu_first_values ${dt_col} dt_first)
list(GET dtu_last_values ${dt_col} dt_last)
string(REGEX MATCH "dt lowered to ([0-9.e+-]+) at step" _ "${run_out}")
set(dt_printed ${CMAKE_MATCH_1})
execute_process(COMMAND printf "%.4g" ${dt_last} OUTPUT_VARIABLE dt_last4)
if(NOT dt_last LESS dt_first OR NOT dt_last4 STREQUAL dt_printed)
  message(FATAL_ERROR "dt_update: history dt ${dt_first} at the start, ${dt_last} (${dt_last4}) "
                      "at the end; the run printed 'dt lowered to ${dt_printed}'")
endif()

# Ctrl-C: a long run interrupted by SIGINT ends with 130, a checkpoint and finished files. The
# signal is sent once the run is stepping (its first checkpoint, at step 1000, exists), not after a
# fixed delay, which a loaded machine could spend before the run installs its handler.
find_program(SH sh)
if(SH)
  file(WRITE ${PDK_TEST_DIR}/interrupt.sh [=[
"$1" run "$2" -o intr -q --set solver.steps=100000000 --set output.checkpoint_interval=1000 &
pid=$!
i=0
while [ ! -e intr/bar_checkpoint.h5 ]; do
  if [ $i -ge 6000 ] || ! kill -0 $pid 2>/dev/null; then
    echo "no first checkpoint (the run ended, or 10 minutes passed)"
    kill -KILL $pid 2>/dev/null
    exit 99
  fi
  i=$((i + 1))
  sleep 0.1
done
kill -INT $pid
wait $pid
]=])
  run(130 ${SH} ${PDK_TEST_DIR}/interrupt.sh ${PDK_CLI} ${scene})
  if(NOT run_out MATCHES "interrupted at step [0-9]+ .*--restart")
    message(FATAL_ERROR "no interruption message: ${run_out}")
  endif()
  foreach(f bar.h5 bar.xmf bar_history.csv bar_checkpoint.h5)
    if(NOT EXISTS ${PDK_TEST_DIR}/intr/${f})
      message(FATAL_ERROR "interrupted run did not leave ${f}")
    endif()
  endforeach()
endif()

# bad input: exit 2, file:line: key messages, nothing written
run(2 ${PDK_CLI} run ${scene} -o bad --set geometry.spacing=-1)
if(NOT run_out MATCHES "--set geometry.spacing=-1.*geometry.spacing: must be > 0")
  message(FATAL_ERROR "bad override message: ${run_out}")
endif()
file(WRITE ${PDK_TEST_DIR}/typo.yaml "dimension: 2\ngeometry:\n  spacig: 1e-3\n")
run(2 ${PDK_CLI} check ${PDK_TEST_DIR}/typo.yaml)
if(NOT run_out MATCHES "typo.yaml:3: geometry.spacig: ")
  message(FATAL_ERROR "unknown key message: ${run_out}")
endif()
if(EXISTS ${PDK_TEST_DIR}/bad)
  message(FATAL_ERROR "a rejected run created its output folder")
endif()
run(2 ${PDK_CLI} run)
run(2 ${PDK_CLI} run ${scene} --frobnicate)
run(0 ${PDK_CLI} run --help)
run(0 ${PDK_CLI} check --help)
