# cmake -P script (see CMakeLists.txt): tressvk-viewer in a window under Xvfb (xvfb-run), on lavapipe with
# validation and synchronization validation. Checks exit 0, "validation: 0 message(s)", the step error of one
# frame against the double reference, and that the screenshot shows hair (CHECK renders the same frame without hair and compares). Then the bad input: a missing file and a
# broken one give exit code 2 and a message naming the file, with no window needed to say so.
include("${CMAKE_CURRENT_LIST_DIR}/../cmake/expect_run.cmake")
foreach(var VIEWER CHECK XVFB_RUN OUT_DIR)
  if(NOT ${var})
    message(FATAL_ERROR "run_viewer_test.cmake: ${var} is not set")
  endif()
endforeach()
# xvfb-run -a picks a free display by its lock file, which races with other xvfb-run users on the machine (other
# test runs): when the X server or the window could not be had (and only then), the run is tried once more.
macro(run_in_xvfb)
  execute_process(COMMAND "${XVFB_RUN}" -a -s "-screen 0 640x480x24" ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(err MATCHES "xvfb-run: error|Xvfb failed|cannot open a window")
    message("retrying once: the X server was not available:\n${err}")
    execute_process(COMMAND "${XVFB_RUN}" -a -s "-screen 0 640x480x24" ${ARGN}
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  endif()
endmacro()
file(REMOVE_RECURSE "${OUT_DIR}")
file(MAKE_DIRECTORY "${OUT_DIR}")
set(frames 4)
set(shot "${OUT_DIR}/viewer.png")
# -a: a free display number (tests may run in parallel); 24-bit screen for an 8-bit BGRA swapchain.
run_in_xvfb("${VIEWER}" --frames ${frames} --validation --width 320 --height 180 --screenshot "${shot}" --step-error)
expect_clean_run("tressvk-viewer")
if(NOT out MATCHES "frames: ${frames}\n")
  message(FATAL_ERROR "tressvk-viewer did not show ${frames} frames")
endif()
# The panel's step error, measured on one frame of the scene: the project's bar for one GPU frame against the
# double reference is 1e-5 of the median strand length (tests/plugin/simulation_test.cpp).
if(NOT out MATCHES "step error: ([0-9.eE+-]+) of the median strand length")
  message(FATAL_ERROR "tressvk-viewer --step-error printed no step error")
endif()
set(step_error "${CMAKE_MATCH_1}")
if(NOT step_error LESS_EQUAL 0.00001)
  message(FATAL_ERROR "step error ${step_error} of the median strand length is above 1e-5")
endif()
execute_process(COMMAND "${CHECK}" "${shot}" ${frames} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the screenshot check failed (${rc})\n--- stderr:\n${err}")
endif()

# Bad input: exit code 2 and a message that names the file.
set(missing "${OUT_DIR}/no-such-groom.tvkhair")
execute_process(COMMAND "${VIEWER}" "${missing}" --frames 1 RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "no-such-groom.tvkhair: no such file")
  message(FATAL_ERROR "missing file: expected exit 2 and a message naming it, got ${rc}\n--- stderr:\n${err}")
endif()
set(broken "${OUT_DIR}/broken.tvkhair")
file(WRITE "${broken}" "this is not a baked hair asset\n")
run_in_xvfb("${VIEWER}" "${broken}" --frames 1 --validation)
if(NOT rc EQUAL 2 OR NOT err MATCHES "broken.tvkhair: ")
  message(FATAL_ERROR "broken file: expected exit 2 and a message naming it, got ${rc}\n--- stdout:\n${out}\n--- stderr:\n${err}")
endif()
message("bad input: ${err}")
set(bad_params "${OUT_DIR}/broken.json")
file(WRITE "${bad_params}" "{ \"simulation\": \n")
execute_process(COMMAND "${VIEWER}" --params "${bad_params}" --frames 1 RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "broken.json")
  message(FATAL_ERROR "broken parameter file: expected exit 2 and a message naming it, got ${rc}\n--- stderr:\n${err}")
endif()
message("bad parameters: ${err}")

# Raw TressFX curves, baked in memory by the viewer (skipped without the shared data), and a broken .tfx.
set(tfx "${DATA_DIR}/tressfx/ratboy/Ratboy_mohawk.tfx")
if(DATA_DIR AND EXISTS "${tfx}")
  run_in_xvfb("${VIEWER}" "${tfx}" --frames 2 --validation --width 320 --height 180)
  message("${out}")
  if(NOT rc EQUAL 0 OR NOT out MATCHES "baked in memory" OR NOT out MATCHES "validation: 0 message\\(s\\)")
    message(FATAL_ERROR "tressvk-viewer on ${tfx}: exit ${rc}, expected 0, the in-memory bake and no validation "
                        "messages\n--- stderr:\n${err}")
  endif()
else()
  message("SKIPPED: the .tfx run (${tfx} is absent; set TRESSVK_DATA_DIR to the shared data directory)")
endif()
set(broken_tfx "${OUT_DIR}/broken.tfx")
file(WRITE "${broken_tfx}" "not a TressFX file")
run_in_xvfb("${VIEWER}" "${broken_tfx}" --frames 1)
if(NOT rc EQUAL 2 OR NOT err MATCHES "broken.tfx")
  message(FATAL_ERROR "broken .tfx: expected exit 2 and a message naming it, got ${rc}\n--- stderr:\n${err}")
endif()
message("broken .tfx: ${err}")
