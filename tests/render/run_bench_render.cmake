# cmake -P script: `tressvk-bench render` on lavapipe with validation + synchronization validation, small view,
# both paths (and the coverage-driven LOD against all strands, at the end). The compute path's JSON holds the
# issue's keys and meets the error targets; the raster path's error is measured (its frame against the reference
# layer over the same frame without hair), and the measure's own check (the compute path's frame through the same
# comparison) stays near the compute path's layer error.

# `tressvk-bench render` on the small test view with validation and the ARGS given, its JSON into `j` (caller's
# scope); fails naming LABEL when the run fails or any of KEYS is missing or null.
function(run_render json label)
  cmake_parse_arguments(R "" "" "ARGS;KEYS" ${ARGN})
  file(REMOVE "${json}")
  file(MAKE_DIRECTORY "${OUT_DIR}")
  execute_process(COMMAND "${BENCH}" render --sample sphere --guides 200 --follows 3 --width 160 --height 120
                          --frames 2 --warmup 1 ${R_ARGS} --validation --json "${json}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "tressvk-bench render ${label} failed (${rc}):\n${err}")
  endif()
  file(READ "${json}" doc)
  foreach(key ${R_KEYS})
    string(JSON v ERROR_VARIABLE missing GET "${doc}" ${key})
    if(missing OR v STREQUAL "" OR v STREQUAL "null")
      message(FATAL_ERROR "${label}: key ${key} missing or null in ${json}")
    endif()
  endforeach()
  set(j "${doc}" PARENT_SCOPE)
endfunction()

foreach(path compute raster)
  run_render("${OUT_DIR}/${path}.json" "--path ${path}" ARGS --path ${path}
             KEYS device path width height strands_drawn gpu_ms_shadow gpu_ms_shading error_mean error_p99 error_max
                  hair_pixels)
  string(JSON mean GET "${j}" error_mean)
  string(JSON p99 GET "${j}" error_p99)
  string(JSON pixels GET "${j}" hair_pixels)
  message("--path ${path}: error mean ${mean}/255, p99 ${p99}/255 over ${pixels} hair pixels")
  if(pixels LESS 200)
    message(FATAL_ERROR "--path ${path}: only ${pixels} hair pixels")
  endif()
  if(path STREQUAL "compute")
    # The issue's targets, not a tolerance (compute_test.cpp says why they hold).
    if(mean GREATER 1.0 OR p99 GREATER 8.0)
      message(FATAL_ERROR "compute path: error mean ${mean} or p99 ${p99} over the targets 1 / 8")
    endif()
  else()
    string(JSON check GET "${j}" check_compute_frame_error_mean)
    message("raster path: the measure's check on the compute path's frame, mean ${check}/255")
    # Measured 0.3-0.4/255 (lavapipe and an NVIDIA H100): 8-bit frames and the composite's blend; frames that do
    # not line up or a wrong blend formula move it by whole levels.
    if(check GREATER 1.5)
      message(FATAL_ERROR "raster path: the frame comparison's own check is off (${check}/255)")
    endif()
  endif()
endforeach()

# The coverage-driven LOD with --error-vs-full: the LOD frame against the sorted reference of ALL strands (the same
# frame rendered without LOD), validation-clean. Its own error (against the thinned strands' reference) meets the
# targets; the error against all strands is recorded, not bounded here (a tenth-of-a-pixel view of 800 strands
# thinned to a quarter is a different sample of the hair: measured mean 18/255 on lavapipe); the summed alpha stays
# within 10 % of the full reference's (measured +5 %: 185 wide strands for 800 thin ones).
run_render("${OUT_DIR}/lod.json" "--lod-target-px 1 --error-vs-full" ARGS --lod-target-px 1 --error-vs-full
           KEYS error_vs_full_mean error_vs_full_p99 error_vs_full_max full_strands coverage_vs_full)
string(JSON drawn GET "${j}" strands_drawn)
string(JSON total GET "${j}" full_strands)
string(JSON mean GET "${j}" error_mean)
string(JSON p99 GET "${j}" error_p99)
string(JSON cover GET "${j}" coverage_vs_full)
string(JSON full_mean GET "${j}" error_vs_full_mean)
message("LOD by coverage: ${drawn} of ${total} strands, error mean ${mean}/255 (vs all strands ${full_mean}), summed alpha ${cover} of the full reference's")
if(NOT drawn LESS total)
  message(FATAL_ERROR "--lod-target-px 1: no strand was thinned (${drawn} of ${total})")
endif()
if(mean GREATER 1.0 OR p99 GREATER 8.0)
  message(FATAL_ERROR "LOD frame: error mean ${mean} or p99 ${p99} against its own reference over the targets 1 / 8")
endif()
if(cover LESS 0.9 OR cover GREATER 1.1)
  message(FATAL_ERROR "LOD frame: summed alpha ${cover} of the full reference's (coverage not kept)")
endif()
