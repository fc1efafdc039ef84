# cmake -P script (see CMakeLists.txt): the demo's video and poster output, its errors, and the groom chain a
# user runs (export the sample scalp, grow a groom on it with tressvk-bake, show it with the demo).
foreach(var DEMO BAKE OUT_DIR)
  if(NOT ${var})
    message(FATAL_ERROR "run_demo_video_test.cmake: ${var} is not set")
  endif()
endforeach()
file(REMOVE_RECURSE "${OUT_DIR}")
file(MAKE_DIRECTORY "${OUT_DIR}/frames")

function(run_checked expect_rc)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL expect_rc)
    message(FATAL_ERROR "expected exit ${expect_rc}, got ${rc}: ${ARGN}\n--- stdout:\n${out}\n--- stderr:\n${err}")
  endif()
  set(last_out "${out}" PARENT_SCOPE)
  set(last_err "${err}" PARENT_SCOPE)
endfunction()

# 1. Video and poster, validation on: an MP4 and a PNG, no PNG sequence.
run_checked(0 "${DEMO}" --frames 4 --width 96 --height 64 --guides 100 --follows 1 --validation
            --out "${OUT_DIR}/frames" --video "${OUT_DIR}/demo.mp4" --poster "${OUT_DIR}/poster.png" --poster-frame 3)
if(NOT last_out MATCHES "validation: 0 message\\(s\\)")
  message(FATAL_ERROR "the video run was not validation-clean\n${last_out}\n${last_err}")
endif()
foreach(f demo.mp4 poster.png)
  if(NOT EXISTS "${OUT_DIR}/${f}")
    message(FATAL_ERROR "tressvk-demo --video did not write ${OUT_DIR}/${f}")
  endif()
endforeach()
file(SIZE "${OUT_DIR}/demo.mp4" size)
if(size LESS 1000)
  message(FATAL_ERROR "demo.mp4 is only ${size} bytes")
endif()
file(GLOB pngs "${OUT_DIR}/frames/*.png")
if(pngs)
  message(FATAL_ERROR "--video should not also write PNG frames: ${pngs}")
endif()

# 2. No ffmpeg: exit 3, a message that says so, and no video.
run_checked(3 "${CMAKE_COMMAND}" -E env PATH=/nonexistent "${DEMO}" --frames 2 --width 64 --height 64
            --video "${OUT_DIR}/none.mp4")
if(NOT last_err MATCHES "needs ffmpeg" OR EXISTS "${OUT_DIR}/none.mp4")
  message(FATAL_ERROR "missing ffmpeg: unclear message or a file left behind\n${last_err}")
endif()

# 3. A broken parameter file: exit 1 naming the file and the field, before any rendering.
file(WRITE "${OUT_DIR}/broken.json" "{\"material\": {\"strand_widht\": 0.001}}")
run_checked(1 "${DEMO}" --frames 1 --params "${OUT_DIR}/broken.json" --out "${OUT_DIR}/frames")
if(NOT last_err MATCHES "broken.json: material.strand_widht: unknown field")
  message(FATAL_ERROR "broken parameter file: unclear message\n${last_err}")
endif()

# 4. The groom chain: the sample's scalp, a curly groom grown on it, shown on the sample's head mesh.
run_checked(0 "${DEMO}" --export-head "${OUT_DIR}/head")
run_checked(0 "${BAKE}" groom --scalp "${OUT_DIR}/head/scalp.obj" --preset curly --guides 200 --follow 1
            -o "${OUT_DIR}/curly.tvkhair")
run_checked(0 "${DEMO}" --asset "${OUT_DIR}/curly.tvkhair" --mesh "${OUT_DIR}/head/head.obj" --frames 2
            --width 96 --height 96 --validation --save-params "${OUT_DIR}/params.json" --out "${OUT_DIR}/frames")
run_checked(0 "${DEMO}" --asset "${OUT_DIR}/curly.tvkhair" --frames 1 --width 64 --height 64
            --params "${OUT_DIR}/params.json" --out "${OUT_DIR}/frames")
message("video, poster, errors and the groom chain all behaved")
