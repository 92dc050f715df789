# Runs PROGRAM with ARGS (a ;-list), then checks the exit code against EXPECT_EXIT and the combined
# standard output and error against EXPECT_REGEX. A crash shows as a non-numeric result and fails.
execute_process(COMMAND ${PROGRAM} ${ARGS} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(all "${out}${err}")
if(NOT "${result}" STREQUAL "${EXPECT_EXIT}")
  message(FATAL_ERROR "exit ${result}, expected ${EXPECT_EXIT}; output:\n${all}")
endif()
if(NOT "${all}" MATCHES "${EXPECT_REGEX}")
  message(FATAL_ERROR "output does not match '${EXPECT_REGEX}':\n${all}")
endif()
message(STATUS "ok: exit ${result}\n${all}")
