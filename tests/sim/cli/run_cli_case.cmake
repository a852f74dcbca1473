# Runs a host tool (kestrel-sim, kestrel-replay) with ARGS (a ;-list) and checks its exit status and that stderr contains
# EXPECT. Used for the usage-error contract: exit status 2 with a message naming the culprit.
separate_arguments(args UNIX_COMMAND "${ARGS}")
execute_process(COMMAND ${SIM} ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL ${WANT_RC})
  message(FATAL_ERROR "exit status ${rc}, wanted ${WANT_RC}\nstderr: ${err}")
endif()
string(FIND "${err}" "${EXPECT}" pos)
if(pos EQUAL -1)
  message(FATAL_ERROR "stderr lacks '${EXPECT}':\n${err}")
endif()
