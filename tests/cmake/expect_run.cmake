# Checks shared by the cmake -P test scripts, on the variables of the caller's last
#   execute_process(COMMAND ... RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
# include("${CMAKE_CURRENT_LIST_DIR}/../cmake/expect_run.cmake") from tests/<area>/<script>.cmake.

# The run named `what` exited with `expected` (a crash or another code fails the test, with both outputs).
function(expect_exit_code expected what)
  if(NOT rc EQUAL ${expected})
    message(FATAL_ERROR "${what} exited with ${rc}, expected ${expected}\n--- stdout:\n${out}\n--- stderr:\n${err}")
  endif()
endfunction()

# The run named `what` exited 0 and reported "validation: 0 message(s)"; its output is echoed into the test log.
function(expect_clean_run what)
  message("${out}")
  expect_exit_code(0 "${what}")
  if(NOT out MATCHES "validation: 0 message\\(s\\)")
    message(FATAL_ERROR "${what} did not report a validation-clean run\n--- stderr:\n${err}")
  endif()
endfunction()
