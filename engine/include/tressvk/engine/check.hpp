// Error handling inside the engine: Vulkan failures become exceptions that name the call and its VkResult.
// The engine is host code (C++); nothing here crosses the plugin's C interface.
#pragma once

#include <volk.h>

#include <stdexcept>
#include <string>

namespace tressvk::engine {

// Thrown by every engine function that fails; the message says what failed and why.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Thrown for a Vulkan call that returned an error code.
class VulkanError : public Error {
 public:
  VulkanError(const char* what, VkResult result);
  VkResult result() const { return result_; }

 private:
  VkResult result_;
};

const char* vk_result_name(VkResult result);

// Throws VulkanError when `result` is negative (an error); positive codes (VK_INCOMPLETE...) are not errors.
inline void vk_check(VkResult result, const char* what) {
  if (result < 0) throw VulkanError(what, result);
}

}  // namespace tressvk::engine
