# tressvk_bake_hair(OUTPUT <file.tvkhair> INPUT <file> [<file>...] [TARGET <name>] [OPTIONS <tressvk-bake options>...]
#                   [DEPENDS <extra files>...])
#
# Adds a build rule that bakes hair with tressvk-bake. It re-runs when an input, an extra dependency or the baker
# itself changes; since bakes are deterministic, unchanged inputs give unchanged bytes and build caches work.
# A `--bones FILE` (or `--bones=FILE`) in OPTIONS is tracked as an input too, so it need not be repeated in DEPENDS.
# Relative INPUT and --bones paths are taken from the current source directory, a relative OUTPUT from the current binary
# directory. With TARGET, a target of that name (built by default) owns the output; otherwise list the output in
# the sources or DEPENDS of something you build. Works in the TressVK tree (the `tressvk-bake` target) and from an
# installed package (`find_package(TressVK)` provides the imported `tressvk::tressvk-bake`).
#
# Example: tressvk_bake_hair(OUTPUT hair.tvkhair INPUT hair.obj TARGET bake_hair OPTIONS --vertices 24 --follow 2)
function(tressvk_bake_hair)
  cmake_parse_arguments(PARSE_ARGV 0 ARG "" "OUTPUT;TARGET" "INPUT;OPTIONS;DEPENDS")
  if(NOT ARG_OUTPUT OR NOT ARG_INPUT)
    message(FATAL_ERROR "tressvk_bake_hair: OUTPUT and INPUT are required")
  endif()
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "tressvk_bake_hair: unexpected arguments: ${ARG_UNPARSED_ARGUMENTS}")
  endif()
  if(TARGET tressvk-bake)
    set(baker tressvk-bake)
    set(baker_dependency tressvk-bake)  # target-level and file-level: re-bake when the baker is rebuilt
  elseif(TARGET tressvk::tressvk-bake)
    set(baker tressvk::tressvk-bake)
    set(baker_dependency "$<TARGET_FILE:tressvk::tressvk-bake>")
  else()
    message(FATAL_ERROR "tressvk_bake_hair: no tressvk-bake target (find_package(TressVK) first)")
  endif()
  cmake_path(ABSOLUTE_PATH ARG_OUTPUT BASE_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}" OUTPUT_VARIABLE output)
  set(inputs "")
  foreach(input IN LISTS ARG_INPUT)
    cmake_path(ABSOLUTE_PATH input BASE_DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}" OUTPUT_VARIABLE abs)
    list(APPEND inputs "${abs}")
  endforeach()
  # Options that name files: the file is an input of the bake (re-bake when it changes) and a relative path is taken
  # from the source directory, like INPUT.
  set(options "")
  set(option_inputs "")
  set(next_is_file OFF)
  foreach(opt IN LISTS ARG_OPTIONS)
    if(next_is_file)
      cmake_path(ABSOLUTE_PATH opt BASE_DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}" OUTPUT_VARIABLE opt)
      list(APPEND option_inputs "${opt}")
      set(next_is_file OFF)
    elseif(opt STREQUAL "--bones")
      set(next_is_file ON)
    elseif(opt MATCHES "^--bones=(.+)$")
      cmake_path(ABSOLUTE_PATH CMAKE_MATCH_1 BASE_DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}" OUTPUT_VARIABLE file)
      list(APPEND option_inputs "${file}")
      set(opt "--bones=${file}")
    endif()
    list(APPEND options "${opt}")
  endforeach()
  if(next_is_file)
    message(FATAL_ERROR "tressvk_bake_hair: --bones needs a file")
  endif()
  cmake_path(GET output PARENT_PATH output_dir)
  cmake_path(GET output FILENAME output_name)
  add_custom_command(
    OUTPUT "${output}"
    COMMAND "${CMAKE_COMMAND}" -E make_directory "${output_dir}"
    COMMAND ${baker} ${inputs} -o "${output}" --quiet ${options}
    DEPENDS ${inputs} ${option_inputs} ${ARG_DEPENDS} ${baker_dependency}
    COMMENT "Baking hair ${output_name}"
    VERBATIM)
  if(ARG_TARGET)
    add_custom_target(${ARG_TARGET} ALL DEPENDS "${output}")
  endif()
endfunction()
