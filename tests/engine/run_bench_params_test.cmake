# cmake -P script (see CMakeLists.txt): tressvk-bench compare --params reads the parameter file the demo and the
# viewer write, options on the command line override it, and a broken file is refused naming the file.
include("${CMAKE_CURRENT_LIST_DIR}/../cmake/expect_run.cmake")
foreach(var BENCH OUT_DIR)
  if(NOT ${var})
    message(FATAL_ERROR "run_bench_params_test.cmake: ${var} is not set")
  endif()
endforeach()
file(REMOVE_RECURSE "${OUT_DIR}")
file(MAKE_DIRECTORY "${OUT_DIR}")
file(WRITE "${OUT_DIR}/tuned.json" [=[
{ "tressvk_params": 1,
  "simulation": { "local_iterations": 3, "length_iterations": 2 },
  "settings": { "step_rate": 120 } }
]=])
set(common compare --builtin straight --guides 16 --scene settle --frames 2 --warmup 0 --no-trajectory)

function(run_bench json)
  execute_process(COMMAND "${BENCH}" ${common} ${ARGN} --json "${json}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "tressvk-bench ${ARGN} failed (${rc}):\n${out}\n${err}")
  endif()
  file(READ "${json}" text)
  string(JSON rate GET "${text}" settings step_rate_hz)
  string(JSON local GET "${text}" settings local_iterations)
  string(JSON length GET "${text}" settings length_iterations)
  set(rate "${rate}" PARENT_SCOPE)
  set(local "${local}" PARENT_SCOPE)
  set(length "${length}" PARENT_SCOPE)
endfunction()

run_bench("${OUT_DIR}/file.json" --params "${OUT_DIR}/tuned.json")
if(NOT rate EQUAL 120 OR NOT local EQUAL 3 OR NOT length EQUAL 2)
  message(FATAL_ERROR "--params: expected 120 Hz, 3 local and 2 length iterations, got ${rate} Hz, ${local}, ${length}")
endif()
run_bench("${OUT_DIR}/override.json" --params "${OUT_DIR}/tuned.json" --step-rate 240 --local-iterations 1)
if(NOT rate EQUAL 240 OR NOT local EQUAL 1 OR NOT length EQUAL 2)
  message(FATAL_ERROR "--params with overrides: expected 240 Hz, 1 local and 2 length iterations, got ${rate} Hz, ${local}, ${length}")
endif()

file(WRITE "${OUT_DIR}/broken.json" "{ \"tressvk_params\": 1, \"simulation\": { \"local_iterations\": \"three\" } }")
execute_process(COMMAND "${BENCH}" ${common} --params "${OUT_DIR}/broken.json" --json "${OUT_DIR}/broken-out.json"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
expect_exit_code(1 "tressvk-bench with a broken parameter file")
if(NOT err MATCHES "broken\\.json" OR NOT err MATCHES "local_iterations")
  message(FATAL_ERROR "the error should name the file and the field:\n${err}")
endif()
if(EXISTS "${OUT_DIR}/broken-out.json")
  message(FATAL_ERROR "no JSON should be written for a refused parameter file")
endif()
message(STATUS "bench --params: file read (120 Hz, 3+2 iterations), overrides applied, broken file refused")
