# The example programs (examples/) run and print what their comments promise:
# - example_lattice_forces: a uniformly stretched PMB block has zero force on its centre particle
#   (each bond there is matched by its opposite one, so only round-off remains: below 1e-9 of one
#   bond's pull) and an energy below the continuum's 9/2 K s^2 (the surface particles miss part of
#   their family) but above half of it (12^3 particles, horizon 3: the surface layer of 3 particles
#   holds 1 - (6/12)^3 = 7/8 of the block, each particle there keeping at least half its bonds);
# - example_point_cloud_static: Newton on a jittered 2-D cloud gives a bar modulus within 10% of the
#   plane-strain E / (1 - nu^2) (measured 3.5% above: free-surface layers one horizon thick on a bar
#   20 spacings high, and the cloud's irregularity);
# - example_scene_run: runs a shipped scene (shortened) through pdk_sim_run and writes its files.
# labels: physics
cmake_minimum_required(VERSION 3.25)
set(ex ${PDK_BUILD_DIR}/examples)
if(NOT EXISTS ${ex}/example_lattice_forces)
  message("pdk-test-skip: the examples are not built (PDK_BUILD_EXAMPLES=OFF)")
  return()
endif()
file(REMOVE_RECURSE ${PDK_TEST_DIR})
file(MAKE_DIRECTORY ${PDK_TEST_DIR})

include(${CMAKE_CURRENT_LIST_DIR}/script_run.cmake)

run(${ex}/example_lattice_forces 12)
if(NOT run_out MATCHES "centre force density ([-+.e0-9]+) N/m\\^3 \\(a single bond's pull: ([-+.e0-9]+)\\)")
  message(FATAL_ERROR "example_lattice_forces printed:\n${run_out}")
endif()
set(fc ${CMAKE_MATCH_1})
set(fb ${CMAKE_MATCH_2})
if(NOT run_out MATCHES "ratio ([.0-9]+)\\)")
  message(FATAL_ERROR "example_lattice_forces printed no energy ratio:\n${run_out}")
endif()
set(ratio ${CMAKE_MATCH_1})
# the printed values are %.3e: compare their decimal exponents (math(EXPR) is integer only)
string(REGEX REPLACE ".*e([-+][0-9]+)$" "\\1" efc "${fc}")
string(REGEX REPLACE ".*e([-+][0-9]+)$" "\\1" efb "${fb}")
math(EXPR gap "${efb} - ${efc}")
if(gap LESS 10)
  message(FATAL_ERROR "centre force ${fc} is not below 1e-9 of one bond's pull ${fb}")
endif()
if(ratio GREATER_EQUAL 1.0 OR ratio LESS_EQUAL 0.5)
  message(FATAL_ERROR "energy ratio ${ratio} outside (0.5, 1)")
endif()

run(${ex}/example_point_cloud_static)
if(NOT run_out MATCHES "R L / \\(H u\\) = ([.0-9]+) GPa, E / \\(1 - nu\\^2\\) = ([.0-9]+) GPa")
  message(FATAL_ERROR "example_point_cloud_static printed:\n${run_out}")
endif()
set(Eb ${CMAKE_MATCH_1})
set(Ep ${CMAKE_MATCH_2})
# within 10%: compare Eb against 0.9 Ep and 1.1 Ep with integer arithmetic on MPa
string(REGEX REPLACE "\\..*" "" Eb_i "${Eb}")
string(REGEX REPLACE "\\..*" "" Ep_i "${Ep}")
math(EXPR lo "${Ep_i} * 9 / 10")
math(EXPR hi "${Ep_i} * 11 / 10 + 1")
if(Eb_i LESS lo OR Eb_i GREATER hi)
  message(FATAL_ERROR "bar modulus ${Eb} GPa not within 10% of ${Ep} GPa")
endif()

run(${ex}/example_scene_run ${PDK_SOURCE_DIR}/scenes/bar_tension.yaml ${PDK_TEST_DIR}/bar
    solver.end_time=2e-5)
if(NOT run_out MATCHES "done: [0-9]+ steps")
  message(FATAL_ERROR "example_scene_run printed:\n${run_out}")
endif()
foreach(f bar_tension_history.csv bar_tension.h5 bar_tension.xmf bar_tension_checkpoint.h5)
  if(NOT EXISTS ${PDK_TEST_DIR}/bar/${f})
    message(FATAL_ERROR "example_scene_run did not write ${f}")
  endif()
endforeach()
