# libpdk.so exports the public API and nothing else: every function declared in include/pdk/*.h
# is a dynamic symbol of the library (it carries PDK_EXPORT, include/pdk/export.h), and every
# symbol the library defines in its dynamic table is one of those functions (the library is
# compiled with hidden visibility; internal functions and data stay local, so an application
# cannot come to depend on them and they do not clash with its own names).
# The declared functions are read from the preprocessed headers (comments and macros resolved):
# every name pdk_* followed by "(" except a function-pointer name "(*pdk_...)".
# labels: unit
cmake_minimum_required(VERSION 3.25)
file(REMOVE_RECURSE ${PDK_TEST_DIR})
file(MAKE_DIRECTORY ${PDK_TEST_DIR})

if(NOT CMAKE_NM OR NOT EXISTS "${CMAKE_NM}")
  message("pdk-test-skip: no nm program (CMAKE_NM '${CMAKE_NM}') to list the library's symbols")
  return()
endif()

# ---- the declared public functions --------------------------------------------------------------
file(GLOB headers RELATIVE ${PDK_SOURCE_DIR}/include ${PDK_SOURCE_DIR}/include/pdk/*.h)
set(tu "")
foreach(h ${headers})
  string(APPEND tu "#include \"${h}\"\n")
endforeach()
file(WRITE ${PDK_TEST_DIR}/all_headers.c "${tu}")
execute_process(COMMAND ${CMAKE_C_COMPILER} -E -P -I${PDK_SOURCE_DIR}/include
                        -I${PDK_BUILD_DIR}/include ${PDK_TEST_DIR}/all_headers.c
                RESULT_VARIABLE rc OUTPUT_VARIABLE pp ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "preprocessing the public headers failed (exit ${rc}):\n${err}")
endif()
string(REGEX REPLACE "\\([ \t]*\\*[ \t]*pdk_[A-Za-z0-9_]*" "(*" pp "${pp}") # function pointers
string(REGEX MATCHALL "pdk_[A-Za-z0-9_]*[ \t\n]*\\(" calls "${pp}")
set(declared "")
foreach(c ${calls})
  string(REGEX REPLACE "[ \t\n]*\\($" "" c "${c}")
  list(APPEND declared ${c})
endforeach()
list(REMOVE_DUPLICATES declared)
list(SORT declared)
list(LENGTH declared num_declared)
if(num_declared LESS 100)
  message(FATAL_ERROR "found only ${num_declared} functions in include/pdk/*.h: the header scan "
                      "is broken (${declared})")
endif()

# ---- the library's exported symbols ------------------------------------------------------------
execute_process(COMMAND ${CMAKE_NM} -D --defined-only ${PDK_LIB}
                RESULT_VARIABLE rc OUTPUT_VARIABLE nm_out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${CMAKE_NM} -D --defined-only ${PDK_LIB} failed (exit ${rc}):\n${err}")
endif()
string(REPLACE "\n" ";" nm_lines "${nm_out}")
set(exported "")
set(extra "")
foreach(line ${nm_lines})
  # "<address> <type> <name>"; the linker's own markers (_init, _edata, ...) are not pdk's
  if(NOT line MATCHES "^[0-9a-fA-F]* *([A-Za-z]) ([^ ]+)$")
    continue()
  endif()
  set(type ${CMAKE_MATCH_1})
  set(name ${CMAKE_MATCH_2})
  if(name MATCHES "^(_init|_fini|_edata|_end|__bss_start)$")
    continue()
  endif()
  list(APPEND exported ${name})
  if(NOT name IN_LIST declared)
    list(APPEND extra "${name} (${type})")
  elseif(NOT type MATCHES "^[TtWi]$")
    list(APPEND extra "${name} (${type}: not a function)")
  endif()
endforeach()
set(missing "")
foreach(name ${declared})
  if(NOT name IN_LIST exported)
    list(APPEND missing ${name})
  endif()
endforeach()

list(LENGTH exported num_exported)
set(msg "")
if(extra)
  list(LENGTH extra n)
  string(REPLACE ";" "\n  " e "${extra}")
  string(APPEND msg "${PDK_LIB} exports ${n} symbol(s) not declared in include/pdk/*.h (internal "
                    "functions must stay hidden: no PDK_EXPORT outside include/pdk/):\n  ${e}\n")
endif()
if(missing)
  list(LENGTH missing n)
  string(REPLACE ";" "\n  " m "${missing}")
  string(APPEND msg "${n} function(s) declared in include/pdk/*.h are not exported by "
                    "${PDK_LIB} (declare them with PDK_EXPORT, include/pdk/export.h, and define "
                    "them in the library):\n  ${m}\n")
endif()
if(msg)
  message(FATAL_ERROR "${msg}")
endif()
