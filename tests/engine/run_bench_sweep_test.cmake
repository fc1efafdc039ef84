# cmake -P script (see CMakeLists.txt): `tressvk-bench sweep` in a lavapipe-sized configuration with validation +
# synchronization validation: two step rates and two vertex counts on two scenes write one CSV and JSON row per
# configuration and scene, with a finite model error, the step error within the reference agreement bar (1e-5 of the
# median strand length) and the default marked; bad input is refused naming the option, writing nothing. Timings
# are not asserted (speed lives in the bench's numbers).
foreach(var BENCH OUT_DIR)
  if(NOT ${var})
    message(FATAL_ERROR "run_bench_sweep_test.cmake: ${var} is not set")
  endif()
endforeach()
include("${CMAKE_CURRENT_LIST_DIR}/../cmake/expect_run.cmake")
file(REMOVE_RECURSE "${OUT_DIR}")
file(MAKE_DIRECTORY "${OUT_DIR}")
set(json "${OUT_DIR}/sweep.json")
set(csv "${OUT_DIR}/sweep.csv")
# (--warmup-ms-max 0: one warm-up frame, not a warm-up until the frame time settles, which takes thousands of these)
# (--model follow-the-leader: the default row it expects is that model's, 240 Hz with 2 iterations, whatever
# TRESSVK_SIM_MODEL says; the sweep's mechanics are the same for every model)
execute_process(COMMAND "${BENCH}" sweep --model follow-the-leader --builtin curly --guides 8 --error-guides 2 --frames 8 --timed-frames 3
                        --warmup-ms 0 --warmup-ms-each 0 --warmup-ms-max 0 --warmup 1 --in-flight 2 --rates 120,240 --local-iterations 2 --length-iterations 1
                        --vertices 16,32 --scenes settle,run --reference-rate 960 --reference-vertices 32 --threads 1
                        --validation --json "${json}" --csv "${csv}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
expect_clean_run("tressvk-bench sweep")
file(READ "${json}" text)
string(JSON rows LENGTH "${text}" rows)
if(NOT rows EQUAL 8)
  message(FATAL_ERROR "sweep: ${rows} rows, expected 2 rates x 2 vertex counts x 2 scenes = 8")
endif()
set(defaults 0)
math(EXPR last "${rows} - 1")
foreach(i RANGE ${last})
  foreach(key gpu_ms_per_frame model_error_rms model_error_max step_error_max stretch_max penetration_depth_rel
              post_contact_speed_mps is_default warmup_ms warmup_settled)
    string(JSON value ERROR_VARIABLE missing GET "${text}" rows ${i} ${key})
    if(missing)
      message(FATAL_ERROR "sweep: row ${i} has no ${key}")
    endif()
    set(${key} "${value}")
  endforeach()
  if(NOT model_error_rms GREATER 0 OR NOT model_error_max GREATER_EQUAL model_error_rms)
    message(FATAL_ERROR "sweep: row ${i}: model error rms ${model_error_rms}, max ${model_error_max}")
  endif()
  if(step_error_max GREATER 1e-5)
    message(FATAL_ERROR "sweep: row ${i}: step error ${step_error_max} over 1e-5")
  endif()
  math(EXPR defaults "${defaults} + ${is_default}")
endforeach()
if(NOT defaults EQUAL 2)
  message(FATAL_ERROR "sweep: ${defaults} rows marked default, expected one per scene (240 Hz, N 32)")
endif()
file(STRINGS "${csv}" lines)
list(LENGTH lines count)
if(NOT count EQUAL 9)
  message(FATAL_ERROR "sweep: ${count} CSV lines, expected a header and 8 rows")
endif()
execute_process(COMMAND "${BENCH}" sweep --rates 1000 --json "${OUT_DIR}/bad.json"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 1 OR NOT err MATCHES "--rates" OR EXISTS "${OUT_DIR}/bad.json")
  message(FATAL_ERROR "sweep --rates 1000: exit ${rc}, expected 1 naming --rates and no output:\n${err}")
endif()
