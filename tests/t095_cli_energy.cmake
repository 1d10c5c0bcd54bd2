# `pdk run` ends an explicit run with its energy account (external work against the change of
# kinetic, strain and dissipated energy since the run's first record) and warns when it is off by
# more than 3% of the energy put in:
#   - the bar of t092 without breaking: the line is printed, off by less than 1e-4 (velocity
#     Verlet with a smooth ramp: measured 7e-6), no warning;
#   - the same bar with PMB critical-stretch breaking (586 bonds break): PMB books what the broken
#     bonds held ("w_broken", the breaking column), so the account closes: no warning and off by
#     less than 1% (measured 0.65%, first order here: the grip's velocity ramps, see t102; before
#     the breaking energy was booked it was off by about 41% of the energy put in);
#   - the two-hole plate at 2 mm with softened stabilization and the family triaxiality to 3 ms:
#     failures and breaks in weakly stabilized families make F jump, which the scene's step does
#     not resolve (docs/validation/plate_two_holes.md, item 8): off by 8.6% (measured), the
#     warning names solver.dt and, since bonds broke under break_stress refit, advises
#     break_stress continuous with dt_update breaks; the run still succeeds (exit 0), the
#     warning is advice;
#   - the same run as that advice says (with critical_stretch 1, item 9): no warning, off by
#     less than 1% (measured 0.021%);
#   - the shipped plate at 1 mm to 3.4 ms with break_stress continuous (and critical_stretch 1)
#     but no dt_update: the stable step falls during the tearing (item 10), off by 10%
#     (measured), and the warning advises dt_update breaks; with it, no warning (measured 0.55%);
#   - the same run at half the time step (solver.safety 0.4 instead of 0.8), as the warning
#     advises: no warning (below 3%, while the run at the scene's step must be above 6%, so at
#     least 2 times closer; measured 0.58%, 15 times closer).
# labels: physics
cmake_minimum_required(VERSION 3.25)
file(REMOVE_RECURSE ${PDK_TEST_DIR})
file(MAKE_DIRECTORY ${PDK_TEST_DIR})

function(run name)
  execute_process(COMMAND ${PDK_CLI} run ${ARGN} -q -o ${name}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  WORKING_DIRECTORY ${PDK_TEST_DIR})
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: exit ${rc}\n${out}${err}")
  endif()
  if(NOT err MATCHES "energy: external work [0-9.e+-]+ = change of kinetic .* off by ([0-9.e+-]+) \\(([0-9.e+-]+)% of the energy put in\\)")
    message(FATAL_ERROR "${name}: no energy line\n${err}")
  endif()
  set(pct ${CMAKE_MATCH_2} PARENT_SCOPE)
  set(run_err "${err}" PARENT_SCOPE)
endfunction()

set(bar ${PDK_SOURCE_DIR}/tests/scenes/t092_bar.yaml)
run(bar_intact ${bar} --set model.critical_stretch=0)
if(pct GREATER 0.01 OR run_err MATCHES "warning")
  message(FATAL_ERROR "bar without breaking: off by ${pct}%, or warned\n${run_err}")
endif()

run(bar_breaking ${bar})
if(NOT run_err MATCHES "breaking 0\\.[1-9]" OR run_err MATCHES "warning|does not book" OR NOT pct LESS 1)
  message(FATAL_ERROR "bar with PMB breaking: nothing booked, warned, or off by ${pct}%\n${run_err}")
endif()

set(plate ${PDK_SOURCE_DIR}/scenes/plate_two_holes.yaml)
run(plate_softened ${plate} --set geometry.spacing=2e-3 --set solver.end_time=3e-3
    --set model.stabilization_softening=plastic --set model.damage_triaxiality=family)
if(NOT run_err MATCHES "warning: the energy balance is off by [0-9.]+% of the energy put in"
   OR NOT run_err MATCHES "solver.dt" OR pct LESS 3
   OR NOT run_err MATCHES "model.break_stress: continuous with solver.dt_update: breaks")
  message(FATAL_ERROR "softened plate at 2 mm: expected a warning (off by ${pct}%)\n${run_err}")
endif()
set(pct_dt ${pct})

set(cont --set geometry.spacing=1e-3 --set solver.end_time=3.4e-3
    --set model.break_stress=continuous --set model.critical_stretch=1)
run(plate_continuous ${plate} ${cont})
if(NOT run_err MATCHES "warning: the energy balance is off by"
   OR NOT run_err MATCHES "the stable step can fall as families lose bonds: solver.dt_update: breaks")
  message(FATAL_ERROR "plate at 1 mm, continuous without dt_update: expected the dt_update "
                      "advice (off by ${pct}%)\n${run_err}")
endif()
run(plate_continuous_dt_update ${plate} ${cont} --set solver.dt_update=breaks)
if(run_err MATCHES "warning" OR NOT pct LESS 1)
  message(FATAL_ERROR "plate at 1 mm, continuous with dt_update: off by ${pct}%, or warned\n"
                      "${run_err}")
endif()

run(plate_softened_advised ${plate} --set geometry.spacing=2e-3 --set solver.end_time=3e-3
    --set model.stabilization_softening=plastic --set model.damage_triaxiality=family
    --set model.break_stress=continuous --set model.critical_stretch=1
    --set solver.dt_update=breaks)
if(run_err MATCHES "warning" OR NOT pct LESS 1)
  message(FATAL_ERROR "softened plate at 2 mm as the warning advises: off by ${pct}%, or "
                      "warned\n${run_err}")
endif()

run(plate_softened_half_dt ${plate} --set geometry.spacing=2e-3 --set solver.end_time=3e-3
    --set model.stabilization_softening=plastic --set model.damage_triaxiality=family
    --set solver.safety=0.4)
if(run_err MATCHES "warning" OR NOT pct_dt GREATER 6)
  message(FATAL_ERROR "half the step: off by ${pct}% (warned) against ${pct_dt}% at the scene's "
                      "step (expected above 6%)\n${run_err}")
endif()
