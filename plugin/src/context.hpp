// Internal state of a TressVK context. Not part of the public interface.
#pragma once

#include <tressvk/tressvk.h>

#include <volk.h>
#include <vk_mem_alloc.h>

#include <cstdarg>
#include <string>

namespace tressvk {

struct Context {
  TvkContextCreateInfo info{};
  VolkDeviceTable vk{};                       // this context's own device-level function table
  PFN_vkGetPhysicalDeviceProperties get_physical_device_properties = nullptr;
  VkPhysicalDeviceProperties device_properties{};
  VmaAllocator allocator = VK_NULL_HANDLE;    // private to TressVK, on the host's device
  uint32_t frames_in_flight = 2;
  std::string last_error;

  // Records an error, forwards it to the host's callback, and returns `result` for `return ctx.fail(...)`.
  TvkResult fail(TvkResult result, const char* format, ...) __attribute__((format(printf, 3, 4)));
  void message(TvkMessageSeverity severity, const char* format, ...) __attribute__((format(printf, 3, 4)));
  // Maps a VkResult to TVK_SUCCESS or a recorded TVK_ERROR_VULKAN naming `what`.
  TvkResult check(VkResult vr, const char* what);
};

const char* vk_result_name(VkResult result);

}  // namespace tressvk

// The opaque handle type of the C interface is the context itself.
struct TvkContext_T : tressvk::Context {};
