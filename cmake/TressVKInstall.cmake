# Installs the plugin (headers, shared library), the command-line tools and a CMake package, so an outside
# project can `find_package(TressVK CONFIG REQUIRED)` and link `tressvk::plugin`.
include(CMakePackageConfigHelpers)

set(TRESSVK_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/TressVK")
set(_tressvk_export_targets tressvk_plugin)
foreach(tool tressvk-bake)
  if(TARGET ${tool})
    list(APPEND _tressvk_export_targets ${tool})
  endif()
endforeach()

install(TARGETS ${_tressvk_export_targets}
  EXPORT TressVKTargets
  RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}"
  LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}")
# The include directory reaches consumers once, through tressvk_plugin's INSTALL_INTERFACE (plugin/CMakeLists.txt);
# an INCLUDES DESTINATION here would list it a second time in the exported targets.
install(DIRECTORY "${PROJECT_SOURCE_DIR}/plugin/include/" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}")
foreach(tool tressvk-demo tressvk-bench)
  if(TARGET ${tool})
    install(TARGETS ${tool} RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
  endif()
endforeach()

install(EXPORT TressVKTargets NAMESPACE tressvk:: DESTINATION "${TRESSVK_INSTALL_CMAKEDIR}")
configure_package_config_file("${CMAKE_CURRENT_LIST_DIR}/TressVKConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/TressVKConfig.cmake" INSTALL_DESTINATION "${TRESSVK_INSTALL_CMAKEDIR}")
write_basic_package_version_file("${PROJECT_BINARY_DIR}/TressVKConfigVersion.cmake"
  COMPATIBILITY SameMajorVersion)
install(FILES "${PROJECT_BINARY_DIR}/TressVKConfig.cmake" "${PROJECT_BINARY_DIR}/TressVKConfigVersion.cmake"
  DESTINATION "${TRESSVK_INSTALL_CMAKEDIR}")
if(EXISTS "${CMAKE_CURRENT_LIST_DIR}/TressVKBake.cmake")
  install(FILES "${CMAKE_CURRENT_LIST_DIR}/TressVKBake.cmake" DESTINATION "${TRESSVK_INSTALL_CMAKEDIR}")
endif()
