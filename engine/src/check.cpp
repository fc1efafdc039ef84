#include <tressvk/engine/check.hpp>

#include <string>

namespace tressvk::engine {

VulkanError::VulkanError(const char* what, VkResult result)
    : Error(std::string(what) + " failed: " + vk_result_name(result)), result_(result) {}

const char* vk_result_name(VkResult result) {
  switch (result) {
#define TVK_CASE(x) \
  case x:           \
    return #x
    TVK_CASE(VK_SUCCESS);
    TVK_CASE(VK_NOT_READY);
    TVK_CASE(VK_TIMEOUT);
    TVK_CASE(VK_EVENT_SET);
    TVK_CASE(VK_EVENT_RESET);
    TVK_CASE(VK_INCOMPLETE);
    TVK_CASE(VK_ERROR_OUT_OF_HOST_MEMORY);
    TVK_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY);
    TVK_CASE(VK_ERROR_INITIALIZATION_FAILED);
    TVK_CASE(VK_ERROR_DEVICE_LOST);
    TVK_CASE(VK_ERROR_MEMORY_MAP_FAILED);
    TVK_CASE(VK_ERROR_LAYER_NOT_PRESENT);
    TVK_CASE(VK_ERROR_EXTENSION_NOT_PRESENT);
    TVK_CASE(VK_ERROR_FEATURE_NOT_PRESENT);
    TVK_CASE(VK_ERROR_INCOMPATIBLE_DRIVER);
    TVK_CASE(VK_ERROR_TOO_MANY_OBJECTS);
    TVK_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED);
    TVK_CASE(VK_ERROR_FRAGMENTED_POOL);
    TVK_CASE(VK_ERROR_UNKNOWN);
    TVK_CASE(VK_ERROR_OUT_OF_POOL_MEMORY);
    TVK_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE);
    TVK_CASE(VK_ERROR_FRAGMENTATION);
    TVK_CASE(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS);
    TVK_CASE(VK_PIPELINE_COMPILE_REQUIRED);
    TVK_CASE(VK_ERROR_VALIDATION_FAILED_EXT);
#undef TVK_CASE
    default:
      return "unknown VkResult";
  }
}

}  // namespace tressvk::engine
