# Runs fastddsgen quietly: its banner and per-file progress ("Loading
# templates...", "Generating ... files...") are dropped, only its errors and
# warnings are printed; a failure or an error line stops the build with them.
# Usage: cmake -DFASTDDSGEN=<exe> -DIDL=<file.idl> -DINCLUDE_DIR=<dir> -DOUT_DIR=<dir>
#              [-DWORK_DIR=<dir>] -P run_fastddsgen.cmake
#
# fastddsgen 2.3 shares files between runs unless told otherwise, so each run
# works in a folder of its own (WORK_DIR, default OUT_DIR/.fastddsgen/<name>)
# and only <name>'s files are copied to OUT_DIR:
# - it preprocesses every file into <temp>/<file>.idl.cc, <temp> being /tmp/
#   on Linux for every process on the machine: all runs that include
#   common.idl rewrite /tmp/common.idl.cc while others parse it ("common.idl:1:0:
#   error: mismatched input '<EOF>'"). -t gives the run its own <temp>;
# - it also generates the code of every included file (common.idl) into -d:
#   written to OUT_DIR, that would overwrite common.* under the common.idl
#   rule's feet, undoing strip_type_registration.cmake.
get_filename_component(name ${IDL} NAME_WE)
if(NOT WORK_DIR)
  set(WORK_DIR ${OUT_DIR}/.fastddsgen/${name})
endif()
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR}/tmp)
execute_process(
  COMMAND ${FASTDDSGEN} -typeobject -cs -replace -I ${INCLUDE_DIR} -d ${WORK_DIR}
          -t ${WORK_DIR}/tmp ${IDL}
  RESULT_VARIABLE result
  OUTPUT_VARIABLE output
  ERROR_VARIABLE errors)

# fastddsgen writes its diagnostics to stdout, coloured; Java traces to stderr.
# Its lines: "file:line:col: error: ...", "ERROR: ...", "ERROR<where>: ...",
# the same with warning. A line saying "error" that is not a warning is an
# error: fastddsgen exits 0 when an included file fails to parse on its own.
string(ASCII 27 escape)
string(REGEX REPLACE "${escape}\\[[0-9;]*m" "" output "${output}")
string(REPLACE "\n" ";" lines "${output}")
set(diagnostics "")
set(has_error FALSE)
foreach(line IN LISTS lines)
  string(TOLOWER "${line}" lower)
  if(lower MATCHES "error|warning")
    string(APPEND diagnostics "${line}\n")
    if(lower MATCHES "error" AND NOT lower MATCHES "(^|: )warning[:<]")
      set(has_error TRUE)
    endif()
  endif()
endforeach()

if(NOT result EQUAL 0 OR has_error)
  if(diagnostics STREQUAL "")
    set(diagnostics "${output}${errors}")  # nothing recognisable: all of it
  endif()
  # Plain message(): FATAL_ERROR would re-wrap the compiler-style lines.
  message("${diagnostics}")
  if(result EQUAL 0)
    message(FATAL_ERROR "fastddsgen reported an error on ${IDL} (though it exited 0)")
  endif()
  message(FATAL_ERROR "fastddsgen failed on ${IDL} (exit ${result})")
endif()
if(NOT diagnostics STREQUAL "")
  message("fastddsgen ${IDL}:\n${diagnostics}")
endif()

# <name>'s own files; the code of the files it includes stays in WORK_DIR.
foreach(suffix "" PubSubTypes TypeObject)
  foreach(ext cxx h)
    file(COPY_FILE ${WORK_DIR}/${name}${suffix}.${ext} ${OUT_DIR}/${name}${suffix}.${ext})
  endforeach()
endforeach()
