// Physical device choice, kept free of Vulkan calls so it can be unit tested.
#pragma once

#include <volk.h>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace tressvk::engine {

struct DeviceCandidate {
  std::string name;
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  uint32_t api_version = 0;
};

struct DeviceChoice {
  std::optional<uint32_t> index;  // into the candidate list; empty on failure
  std::string error;              // why nothing was chosen
};

// Preference order for automatic choice: discrete, integrated, virtual, CPU, other (lower is better).
int device_type_rank(VkPhysicalDeviceType type);
const char* device_type_name(VkPhysicalDeviceType type);

// `selector` empty: the best-ranked device with Vulkan >= `min_api` (ties keep enumeration order).
// `selector` all digits: that enumeration index. Otherwise: the first device whose name contains `selector`
// (case-insensitive). An explicitly chosen device below `min_api` is an error naming the device.
DeviceChoice choose_device(std::span<const DeviceCandidate> candidates, std::string_view selector,
                           uint32_t min_api);

}  // namespace tressvk::engine
