# cmake -P script run by ctest (see CMakeLists.txt): install, configure the consumer, build it, run it.
cmake_minimum_required(VERSION 3.25)

foreach(var BUILD_DIR CONSUMER_SOURCE_DIR WORK_DIR GENERATOR)
  if(NOT ${var})
    message(FATAL_ERROR "run_install_test.cmake: ${var} is not set")
  endif()
endforeach()

set(prefix "${WORK_DIR}/prefix")
set(consumer_build "${WORK_DIR}/consumer-build")
file(REMOVE_RECURSE "${WORK_DIR}")

function(step name)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "install test: ${name} failed (${rc})\n--- command: ${ARGN}\n--- stdout:\n${out}\n--- stderr:\n${err}")
  endif()
  message(STATUS "install test: ${name}: ok")
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

set(config_args)
if(CONFIG)
  set(config_args --config "${CONFIG}")
endif()
step("cmake --install" "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${prefix}" ${config_args})

# What an outside project relies on.
foreach(file include/tressvk/tressvk.h lib/cmake/TressVK/TressVKConfig.cmake
             lib/cmake/TressVK/TressVKConfigVersion.cmake lib/cmake/TressVK/TressVKTargets.cmake)
  if(NOT EXISTS "${prefix}/${file}")
    message(FATAL_ERROR "install test: ${file} is missing from the installed tree ${prefix}")
  endif()
endforeach()
file(GLOB plugin_library "${prefix}/lib*/libtressvk.so*")
if(NOT plugin_library)
  message(FATAL_ERROR "install test: libtressvk.so is missing from ${prefix}/lib")
endif()

# The installed targets name the include directory once (it used to appear twice: INCLUDES DESTINATION and the
# target's INSTALL_INTERFACE).
file(READ "${prefix}/lib/cmake/TressVK/TressVKTargets.cmake" targets_text)
string(REGEX MATCH "INTERFACE_INCLUDE_DIRECTORIES \"([^\"]*)\"" _ "${targets_text}")
set(include_dirs "${CMAKE_MATCH_1}")
list(LENGTH include_dirs include_dir_count)
if(NOT include_dir_count EQUAL 1)
  message(FATAL_ERROR "install test: tressvk::plugin's include directories should be one, are: ${include_dirs}")
endif()
message(STATUS "install test: include directories of tressvk::plugin: ${include_dirs}")

set(compiler_args)
if(C_COMPILER)
  list(APPEND compiler_args "-DCMAKE_C_COMPILER=${C_COMPILER}")
endif()
if(CXX_COMPILER)
  list(APPEND compiler_args "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}")
endif()
# Only the installed prefix: the consumer must not see the source or build tree.
step("configure consumer" "${CMAKE_COMMAND}" -S "${CONSUMER_SOURCE_DIR}" -B "${consumer_build}" -G "${GENERATOR}"
     "-DCMAKE_PREFIX_PATH=${prefix}" -DCMAKE_BUILD_TYPE=Release ${compiler_args})
# tressvk_bake_hair(... OPTIONS --bones FILE): the bones file is an input of the bake rule.
file(READ "${consumer_build}/build.ninja" ninja_text)
string(REGEX MATCH "build [^\n]*never_built\\.tvkhair[^\n]*: CUSTOM_COMMAND[^\n]*" bake_rule "${ninja_text}")
if(NOT bake_rule)
  message(FATAL_ERROR "install test: no bake rule for never_built.tvkhair in ${consumer_build}/build.ninja")
endif()
if(NOT bake_rule MATCHES "hair/skeleton\\.tfxbone")
  message(FATAL_ERROR "install test: the --bones file is not an input of the bake rule:\n${bake_rule}")
endif()
message(STATUS "install test: --bones file tracked by the bake rule")
step("build consumer" "${CMAKE_COMMAND}" --build "${consumer_build}")
foreach(exe tressvk_consumer_c tressvk_consumer_cpp)
  step("run ${exe}" "${consumer_build}/${exe}")
  message(STATUS "${step_output}")
endforeach()

# Installed programs must find the installed libtressvk by themselves (RPATH), not through the build tree.
foreach(tool tressvk-demo tressvk-bake)
  if(EXISTS "${prefix}/bin/${tool}")
    step("run installed ${tool} --help" "${prefix}/bin/${tool}" --help)
  endif()
endforeach()
