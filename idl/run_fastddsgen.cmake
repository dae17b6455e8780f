# Runs fastddsgen quietly: its banner and per-file progress ("Loading
# templates...", "Generating ... files...") are dropped, only its errors and
# warnings are printed; a failure stops the build with them.
# Usage: cmake -DFASTDDSGEN=<exe> -DIDL=<file.idl> -DINCLUDE_DIR=<dir> -DOUT_DIR=<dir>
#              -P run_fastddsgen.cmake
execute_process(
  COMMAND ${FASTDDSGEN} -typeobject -cs -replace -I ${INCLUDE_DIR} -d ${OUT_DIR} ${IDL}
  RESULT_VARIABLE result
  OUTPUT_VARIABLE output
  ERROR_VARIABLE errors)

# fastddsgen writes its diagnostics to stdout, coloured; Java traces to stderr.
string(ASCII 27 escape)
string(REGEX REPLACE "${escape}\\[[0-9;]*m" "" output "${output}")
string(REPLACE "\n" ";" lines "${output}")
set(diagnostics "")
foreach(line IN LISTS lines)
  string(TOLOWER "${line}" lower)
  if(lower MATCHES "error|warning")
    string(APPEND diagnostics "${line}\n")
  endif()
endforeach()

if(NOT result EQUAL 0)
  if(diagnostics STREQUAL "")
    set(diagnostics "${output}${errors}")  # nothing recognisable: all of it
  endif()
  # Plain message(): FATAL_ERROR would re-wrap the compiler-style lines.
  message("${diagnostics}")
  message(FATAL_ERROR "fastddsgen failed on ${IDL} (exit ${result})")
endif()
if(NOT diagnostics STREQUAL "")
  message("fastddsgen ${IDL}:\n${diagnostics}")
endif()
