# Finds every dependency from Debian 12 packages (see scripts/setup-deps.sh). Nothing is vendored.

find_package(Vulkan 1.3 REQUIRED COMPONENTS glslangValidator)

# volk: bookworm's package ships only volk.h and volk.c, no CMake config. Build it here as a small static
# library. Every target that links it gets its own copy of volk's globals inside its own binary; the plugin is
# a shared library with hidden visibility, so its copy never touches the host's function pointers.
find_package(volk CONFIG QUIET)
if(NOT TARGET volk::volk)
  find_path(TRESSVK_VOLK_INCLUDE_DIR volk.h REQUIRED)
  find_file(TRESSVK_VOLK_SOURCE volk.c PATHS "${TRESSVK_VOLK_INCLUDE_DIR}" NO_DEFAULT_PATH REQUIRED)
  add_library(tressvk_volk STATIC "${TRESSVK_VOLK_SOURCE}")
  set_target_properties(tressvk_volk PROPERTIES POSITION_INDEPENDENT_CODE ON C_VISIBILITY_PRESET hidden)
  target_include_directories(tressvk_volk SYSTEM PUBLIC "${TRESSVK_VOLK_INCLUDE_DIR}")
  target_link_libraries(tressvk_volk PUBLIC Vulkan::Headers ${CMAKE_DL_LIBS})
  target_compile_definitions(tressvk_volk PUBLIC VK_NO_PROTOTYPES)
  add_library(volk::volk ALIAS tressvk_volk)
endif()

# VulkanMemoryAllocator: the header package from Debian trixie, unpacked into .deps/ by setup-deps.sh.
find_package(VulkanMemoryAllocator CONFIG REQUIRED)

find_package(glm CONFIG REQUIRED)
# tinyobjloader's version string is "2rc10": a version argument here would fail, so none is given.
find_package(tinyobjloader CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)
find_path(TRESSVK_STB_INCLUDE_DIR stb_image_write.h PATH_SUFFIXES stb REQUIRED)
if(NOT TARGET tressvk_stb)
  add_library(tressvk_stb INTERFACE)
  target_include_directories(tressvk_stb SYSTEM INTERFACE "${TRESSVK_STB_INCLUDE_DIR}")
endif()

if(TRESSVK_BUILD_TESTS)
  find_package(Catch2 3 CONFIG REQUIRED)
  include(Catch)
endif()
