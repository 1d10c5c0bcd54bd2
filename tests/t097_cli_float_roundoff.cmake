# Float storage where round-off, not discretization, dominates is detected and reported: the
# static LPS block of t094 (20 mm tall) with its top pulled 1 um instead of 10 um (mean strain
# 5e-5, largest bond stretch about 1e-4, within 1e4 of the float stretch resolution
# 2^-24 = 6e-8) run with model.precision float ends with a warning naming the key and the ratio;
# the same with precision double, and float at the scene's own 10 um (largest stretch ~1e-3,
# ratio ~1.6e4), give no warning. The runs succeed (exit 0): the warning is advice.
# labels: unit extreme
cmake_minimum_required(VERSION 3.25)
set(scene ${PDK_SOURCE_DIR}/tests/scenes/t094_static.yaml)
file(REMOVE_RECURSE ${PDK_TEST_DIR})
file(MAKE_DIRECTORY ${PDK_TEST_DIR})

foreach(case float:1e-6 double:1e-6 float:1e-5)
  string(REPLACE ":" ";" parts ${case})
  list(GET parts 0 prec)
  list(GET parts 1 pull)
  execute_process(COMMAND ${PDK_CLI} run ${scene} -q -o ${prec}_${pull}
                          --set model.precision=${prec} --set boundary_conditions.1.y=${pull}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  WORKING_DIRECTORY ${PDK_TEST_DIR})
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${case}: exit ${rc}\n${out}${err}")
  endif()
  if(case STREQUAL "float:1e-6")
    if(NOT err MATCHES "warning: model.precision float: the largest bond stretch at the end \\(([0-9.e+-]+)\\) is only ([0-9.e+-]+) times"
       OR NOT err MATCHES "use model.precision: double")
      message(FATAL_ERROR "${case}: no round-off warning\n${err}")
    endif()
    # mean strain 5e-5; the largest bond stretch (near the held corners) within a factor 4 of it
    set(smax ${CMAKE_MATCH_1})
    if(smax LESS 0.00005 OR smax GREATER 0.0002)
      message(FATAL_ERROR "${case}: largest stretch ${smax} is not near the applied 5e-5\n${err}")
    endif()
  elseif(err MATCHES "warning")
    message(FATAL_ERROR "${case}: warned\n${err}")
  endif()
endforeach()
