# cmake -P script (see CMakeLists.txt): tressvk-bench perf on lavapipe with validation + synchronization validation,
# on the default path (the run kernel where the strands fit the device's subgroups, else one thread per strand), the
# one-thread kernel and the pass-per-dispatch path: the JSON has every key the issue asks for and names the kernel
# that ran, the frame kernels record one dispatch per frame whatever the substeps (240 Hz: 4 or 5), the
# pass-per-dispatch path one per pass per substep, and every path's step error is within the reference agreement bar
# (1e-5 of the median strand length). No timing is asserted (speed
# lives in the bench's numbers, not in tests).
foreach(var BENCH OUT_DIR)
  if(NOT ${var})
    message(FATAL_ERROR "run_bench_perf_test.cmake: ${var} is not set")
  endif()
endforeach()
file(REMOVE_RECURSE "${OUT_DIR}")
file(MAKE_DIRECTORY "${OUT_DIR}")

# Runs `tressvk-bench perf ARGS... --json JSON` (with ENV, a list of VAR=VALUE, in its environment) and reads the JSON
# into TEXT; fails the test, naming LABEL, when the run does.
function(run_perf label json env)
  execute_process(COMMAND "${CMAKE_COMMAND}" -E env ${env} "${BENCH}" perf ${ARGN} --json "${json}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "tressvk-bench perf ${label} failed (${rc}):\n${out}\n${err}")
  endif()
  file(READ "${json}" text)
  set(text "${text}" PARENT_SCOPE)
endfunction()

foreach(path default fused passes)
  set(json "${OUT_DIR}/${path}.json")
  set(env_path "${path}")
  if(path STREQUAL "default")
    set(env_path "")
  endif()
  # The plugin's per-pass timestamps are off unless asked for (they add to the frame time); the passes path asks.
  # (Its timings of a frame are read frames_in_flight frames later: 8 timed frames leave some to read.)
  set(timings "")
  set(timing_keys "")
  set(frames 4)
  if(path STREQUAL "passes")
    set(timings --pass-timings)
    set(timing_keys sim_pass_ms_per_frame)
    set(frames 8)
  endif()
  # (The paths are follow-the-leader's kernels: the model is named, so that a run of every test with another model as
  # the default, TRESSVK_SIM_MODEL, still checks them.)
  run_perf("(${path})" "${json}" "TRESSVK_SIM_PATH=${env_path}"
           --builtin curly --guides 40 --follows 1 --scene shake --frames ${frames} --warmup 2 --error-frames 2 --validation
           --warmup-ms 0 --warmup-ms-max 200 --model follow-the-leader ${timings})
  # copy_gb_per_s: the copy kernel's; transfer_copy_gb_per_s: vkCmdCopyBuffer's (both of the frame's bytes).
  # host_ms_per_frame: the CPU time of the plugin's per-frame calls (set_frame, new_frame, cmd_simulate);
  # host_simulate_ms_per_frame: cmd_simulate's alone, a part of it.
  foreach(key gpu_ms_per_frame gpu_ms_per_frame_p99 bytes_per_frame achieved_gb_per_s copy_gb_per_s
              transfer_copy_gb_per_s dispatches_per_frame step_error_max_rel steps_per_frame guide_vertices
              host_ms_per_frame host_ms_per_frame_p99 host_simulate_ms_per_frame ${timing_keys})
    string(JSON value ERROR_VARIABLE missing GET "${text}" ${key})
    if(missing)
      message(FATAL_ERROR "perf (${path}): key ${key} missing from ${json}")
    endif()
    if(NOT value GREATER 0)
      message(FATAL_ERROR "perf (${path}): ${key} is ${value}, expected > 0")
    endif()
    set(${key} "${value}")
  endforeach()
  if(host_ms_per_frame_p99 LESS host_ms_per_frame)
    message(FATAL_ERROR "perf (${path}): host_ms_per_frame_p99 ${host_ms_per_frame_p99} under its median ${host_ms_per_frame}")
  endif()
  if(host_simulate_ms_per_frame GREATER host_ms_per_frame)  # a part of every frame's calls: its median is no more
    message(FATAL_ERROR "perf (${path}): host_simulate_ms_per_frame ${host_simulate_ms_per_frame} over the whole "
                        "calls' ${host_ms_per_frame}")
  endif()
  # The warm-up (at least --warmup frames, then until the frame time settles, here at most 200 ms: the bound keeps
  # the test short on lavapipe, whose frame times wander with the host's load).
  string(JSON warmup_frames GET "${text}" warmup_frames)
  if(warmup_frames LESS 2)
    message(FATAL_ERROR "perf (${path}): ${warmup_frames} warm-up frames, expected at least --warmup 2")
  endif()
  # Sleeping (docs/simulation.md): the threshold in use and the guides asleep after the timed frames (0 in `shake`).
  foreach(key sleep_below guides_asleep warmup_ms warmup_settled clock_probe_ms clock_probe_fastest_ms)
    string(JSON value ERROR_VARIABLE missing GET "${text}" ${key})
    if(missing)
      message(FATAL_ERROR "perf (${path}): key ${key} missing from ${json}")
    endif()
  endforeach()
  # A timed warm-up (--warmup-ms-max 200) times the clock probe in its frames (frame_timing.hpp), under validation.
  string(JSON probe GET "${text}" clock_probe_ms)
  string(JSON fastest GET "${text}" clock_probe_fastest_ms)
  if(NOT probe GREATER 0 OR fastest GREATER probe)
    message(FATAL_ERROR "perf (${path}): clock probe ${probe} ms, fastest ${fastest} ms: expected a probe, the fastest "
                        "no slower than it")
  endif()
  string(JSON kernel ERROR_VARIABLE missing GET "${text}" kernel)
  if(missing)
    message(FATAL_ERROR "perf (${path}): key kernel missing from ${json}")
  endif()
  # The default runs frame(runs4), frame(runs8) or frame, by the groom and the device's subgroups.
  set(expected_kernel "^frame")
  if(path STREQUAL "passes")
    set(expected_kernel "^passes$")
  elseif(path STREQUAL "fused")
    set(expected_kernel "^frame$")
  endif()
  if(NOT kernel MATCHES "${expected_kernel}")
    message(FATAL_ERROR "perf (${path}): kernel '${kernel}', expected ${expected_kernel}")
  endif()
  if(NOT path STREQUAL "passes" AND NOT dispatches_per_frame EQUAL 1)
    message(FATAL_ERROR "perf (${path}): ${dispatches_per_frame} dispatches per frame, expected 1")
  endif()
  if(path STREQUAL "passes" AND NOT dispatches_per_frame GREATER 4)
    message(FATAL_ERROR "perf (passes): ${dispatches_per_frame} dispatches per frame, expected one per pass per substep")
  endif()
  if(step_error_max_rel GREATER 1e-5)
    message(FATAL_ERROR "perf (${path}): step error ${step_error_max_rel} over 1e-5")
  endif()
  message(STATUS "${path} (${kernel}): ${dispatches_per_frame} dispatches/frame, step error ${step_error_max_rel}")
endforeach()

# A crowd (--instances 3): every instance in one tressvk_cmd_simulate, one frame-kernel dispatch each, validation clean
# (the instances' barriers are their own buffers'), the step error the first instance's; then the same crowd's frames
# planned on two threads (--plan-threads 2: tressvk_set_frame and tressvk_plan_frame of distinct instances at once).
foreach(threads 0 2)
  set(json "${OUT_DIR}/crowd-${threads}.json")
  run_perf("--instances 3 --plan-threads ${threads}" "${json}" ""
           --builtin curly --guides 40 --instances 3 --plan-threads ${threads} --scene shake --frames 4 --warmup 2
           --error-frames 1 --validation --warmup-ms 0 --warmup-ms-max 0)
  string(JSON instances GET "${text}" instances)
  string(JSON plan_threads GET "${text}" plan_threads)
  string(JSON dispatches GET "${text}" dispatches_per_frame)
  string(JSON crowd_error GET "${text}" step_error_max_rel)
  if(NOT instances EQUAL 3 OR NOT plan_threads EQUAL threads OR NOT dispatches EQUAL 3)
    message(FATAL_ERROR "perf --instances 3 --plan-threads ${threads}: ${instances} instances, ${plan_threads} plan "
                        "threads, ${dispatches} dispatches per frame, expected 3, ${threads} and 3")
  endif()
  if(crowd_error GREATER 1e-5)
    message(FATAL_ERROR "perf --instances 3 --plan-threads ${threads}: step error ${crowd_error} over 1e-5")
  endif()
  message(STATUS "crowd of 3, ${threads} plan threads: ${dispatches} dispatches/frame, step error ${crowd_error}")
endforeach()

# --draw-strands: the follow hairs of the drawn prefix only (tressvk_set_draw_strands), the step error over those,
# validation clean.
set(json "${OUT_DIR}/draw.json")
run_perf("--draw-strands 60" "${json}" ""
         --builtin curly --guides 40 --follows 2 --draw-strands 60 --scene shake --frames 4 --warmup 2 --error-frames 2
         --validation --warmup-ms 0 --warmup-ms-max 0)
string(JSON draw_strands GET "${text}" draw_strands)
string(JSON draw_error GET "${text}" step_error_max_rel)
if(NOT draw_strands EQUAL 60)
  message(FATAL_ERROR "perf --draw-strands 60: the JSON says ${draw_strands}")
endif()
if(draw_error GREATER 1e-5)
  message(FATAL_ERROR "perf --draw-strands 60: step error ${draw_error} over 1e-5 on the strands written")
endif()
message(STATUS "guides and half a follow layer drawn: step error ${draw_error}")

# --bones drives an asset's bones every frame (a skinned character's CPU time); a groom without bone weights is refused
# before anything runs, exit 1, the message naming the option. (The skinning itself is checked against the reference
# by the plugin's bone-skinned Ratboy test; the bench's bones are the same motion, reference::rocking_bones.)
execute_process(COMMAND "${BENCH}" perf --builtin curly --guides 8 --bones --frames 1 --json "${OUT_DIR}/bones.json"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 1 OR NOT err MATCHES "--bones: the groom curly has no bone weights")
  message(FATAL_ERROR "perf --bones on a groom without bones: exit ${rc}, expected 1 naming --bones:\n${err}")
endif()
if(EXISTS "${OUT_DIR}/bones.json")
  message(FATAL_ERROR "perf --bones refused, but wrote ${OUT_DIR}/bones.json")
endif()
message(STATUS "--bones without bone weights refused: ${err}")
