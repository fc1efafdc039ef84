# cmake -P script: bakes DATA_DIR/tressfx/ratboy/Ratboy_mohawk.tfx with the baker library (BAKE), then runs
# tressvk-demo (DEMO) on it for 3 frames with validation: exit 0, "validation: 0 message(s)", 3 PNGs.
# Without the shared data the test is skipped (SKIP_REGULAR_EXPRESSION "SKIPPED:").
include("${CMAKE_CURRENT_LIST_DIR}/../cmake/expect_run.cmake")
set(tfx "${DATA_DIR}/tressfx/ratboy/Ratboy_mohawk.tfx")
if(NOT EXISTS "${tfx}")
  message("SKIPPED: ${tfx} is absent (set TRESSVK_DATA_DIR to the shared data directory)")
  return()
endif()
file(REMOVE_RECURSE "${OUT_DIR}")
file(MAKE_DIRECTORY "${OUT_DIR}")
execute_process(COMMAND "${BAKE}" "${tfx}" "${OUT_DIR}/ratboy_mohawk.tvkhair" RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "baking ${tfx} failed (${rc}):\n${err}")
endif()
execute_process(COMMAND "${DEMO}" --asset "${OUT_DIR}/ratboy_mohawk.tvkhair" --frames 3 --validation --width 256
                        --height 192 --out "${OUT_DIR}/frames"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
expect_clean_run("tressvk-demo")
foreach(i 0 1 2)
  if(NOT EXISTS "${OUT_DIR}/frames/frame_000${i}.png")
    message(FATAL_ERROR "tressvk-demo did not write ${OUT_DIR}/frames/frame_000${i}.png")
  endif()
endforeach()
