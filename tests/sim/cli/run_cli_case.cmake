# Runs a host tool (kestrel-sim, kestrel-replay, ...) with ARGS (a ;-list) and checks its exit status and that stderr
# (or stdout, with -DSTREAM=stdout) contains EXPECT. Used for the usage-error contract (exit status 2 with a message
# naming the culprit) and for --help (exit status 0, the usage on stdout).
separate_arguments(args UNIX_COMMAND "${ARGS}")
execute_process(COMMAND ${SIM} ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL ${WANT_RC})
  message(FATAL_ERROR "exit status ${rc}, wanted ${WANT_RC}\nstderr: ${err}")
endif()
set(stream stderr)
set(text "${err}")
if(STREAM STREQUAL "stdout")
  set(stream stdout)
  set(text "${out}")
endif()
string(FIND "${text}" "${EXPECT}" pos)
if(pos EQUAL -1)
  message(FATAL_ERROR "${stream} lacks '${EXPECT}':\n${text}")
endif()
