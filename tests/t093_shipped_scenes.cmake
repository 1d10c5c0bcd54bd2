# Every scene shipped in scenes/ is valid: `pdk check` loads it, builds the simulation (particles,
# sets, families, model, solver and its time step) and exits 0. The fine variants are checked with
# their spacing coarsened by an override (their full size is for the documented studies).
# labels: unit
cmake_minimum_required(VERSION 3.25)
file(GLOB scenes ${PDK_SOURCE_DIR}/scenes/*.yaml)
list(LENGTH scenes count)
if(count LESS 3)
  message(FATAL_ERROR "expected the shipped scenes in ${PDK_SOURCE_DIR}/scenes, found ${count}")
endif()
foreach(scene ${scenes})
  set(extra)
  if(scene MATCHES "_fine\\.yaml$")
    set(extra --set geometry.spacing=2.0e-3)
  endif()
  execute_process(COMMAND ${PDK_CLI} check ${scene} ${extra} RESULT_VARIABLE rc
                  OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT out MATCHES "is valid")
    message(FATAL_ERROR "pdk check ${scene} ${extra}: exit ${rc}\n${out}${err}")
  endif()
endforeach()
