# Fails on a lane exchange read under a condition in the simulation shaders (SHADER_DIR): a shuffle needs its source
# lane active, so `c ? lanes_get0(i) : x` or `c && lanes_get0(i).w > 0.5` reads garbage on a GPU wherever c differs
# between lanes (the conservative shape's residual did this: positions of 1e38 on an NVIDIA H100). lavapipe runs a
# subgroup's lanes in SIMD and cannot show it; this check can. Every lane calls the exchange, then selects.
# Heuristic: a line where `?`, `&&` or `||` comes before an exchange call.
set(calls "lanes_get[0-2]?|lanes_max|lanes_min|lanes_any|from_lane|from_before|from_after|runs_min|subgroup[A-Za-z]+")
set(pattern "(\\?|&&|\\|\\|)[^;]*(${calls})\\(")
# The check checks itself on the line that had the bug.
if(NOT "    bool live_2 = v >= 3u && lanes_get0(v >= 2u ? v - 2u : 0u).w > 0.5;" MATCHES "${pattern}")
  message(FATAL_ERROR "the pattern no longer matches the bug it was written for")
endif()
file(GLOB shaders "${SHADER_DIR}/*.glsl" "${SHADER_DIR}/*.comp")
list(LENGTH shaders count)
if(count LESS 5)
  message(FATAL_ERROR "no simulation shaders found in ${SHADER_DIR}")
endif()
set(found "")
foreach(shader IN LISTS shaders)
  file(STRINGS "${shader}" lines)
  set(n 0)
  foreach(line IN LISTS lines)
    math(EXPR n "${n} + 1")
    string(REGEX REPLACE "//.*$" "" code "${line}")
    if(code MATCHES "${pattern}")
      get_filename_component(name "${shader}" NAME)
      string(APPEND found "\n  ${name}:${n}: ${line}")
    endif()
  endforeach()
endforeach()
if(found)
  message(FATAL_ERROR "lane exchange under a condition (get first, then select):${found}")
endif()
message(STATUS "${count} simulation shaders: every lane exchange is unconditional")
