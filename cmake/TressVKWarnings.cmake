# Project-wide compiler settings applied per target with tressvk_target_defaults(<target>).
function(tressvk_target_defaults target)
  target_compile_options(${target} PRIVATE
    $<$<COMPILE_LANG_AND_ID:CXX,GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
      -Wnon-virtual-dtor -Wold-style-cast -Wcast-align -Woverloaded-virtual
      -Wformat=2 -Wimplicit-fallthrough>
    $<$<COMPILE_LANG_AND_ID:C,GNU,Clang>:-Wall -Wextra>)
  if(TRESSVK_WERROR)
    target_compile_options(${target} PRIVATE $<$<COMPILE_LANG_AND_ID:CXX,GNU,Clang>:-Werror>)
  endif()
endfunction()

if(TRESSVK_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()

if(TRESSVK_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "TRESSVK_FUZZ needs clang (libFuzzer): use the `fuzz` preset")
  endif()
  # Coverage feedback from every library, not only the fuzz targets' own files.
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()

if(TRESSVK_PORTABLE)
  # A Debian 12 binary that runs on other glibc >= 2.34 systems: static libstdc++ (not libgcc, which would pull
  # in a GLIBC_2.35 symbol) and a local arc4random (cmake/portable/arc4random.c), which libstdc++.a's random.o
  # references (glibc has it only from 2.36). Build-tree only: nothing installed depends on it.
  add_link_options(-static-libstdc++)
  add_library(tressvk_portable_arc4random OBJECT "${CMAKE_CURRENT_LIST_DIR}/portable/arc4random.c")
  set_target_properties(tressvk_portable_arc4random PROPERTIES POSITION_INDEPENDENT_CODE ON C_VISIBILITY_PRESET hidden)
  link_libraries($<BUILD_INTERFACE:tressvk_portable_arc4random>)
endif()
