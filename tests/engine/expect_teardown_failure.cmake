# cmake -P script: runs PROGRAM, which must exit non-zero and report a validation message at device teardown
# (VUID-vkDestroyDevice-device-00378: an object not destroyed). A crash or a silent pass fails this test.
include("${CMAKE_CURRENT_LIST_DIR}/../cmake/expect_run.cmake")
execute_process(COMMAND "${PROGRAM}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0)
  message(FATAL_ERROR "the leaking program exited 0: the fixture ignored the teardown message\n${out}\n${err}")
endif()
expect_exit_code(1 "the leaking program (the fixture's code; another one is a crash?)")
if(NOT err MATCHES "outside a running test case" OR NOT err MATCHES "vkDestroyDevice")
  message(FATAL_ERROR "the fixture's teardown report is missing\n--- stdout:\n${out}\n--- stderr:\n${err}")
endif()
message(STATUS "the fixture failed the process as it must (exit ${rc})")
