# csv_column(HEADER REGEX OUT): the 0-based index of the first column of the CSV header line
# HEADER whose name (with its unit) matches REGEX, or -1. Used by the CLI tests (cmake -P).
function(csv_column header regex out)
  string(REPLACE "," ";" names "${header}")
  set(index -1)
  set(k 0)
  foreach(name IN LISTS names)
    if(index LESS 0 AND name MATCHES "${regex}")
      set(index ${k})
    endif()
    math(EXPR k "${k} + 1")
  endforeach()
  set(${out} ${index} PARENT_SCOPE)
endfunction()
