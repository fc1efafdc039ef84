#include <tressvk/engine/device_select.hpp>

#include <algorithm>
#include <cctype>
#include <string>

namespace tressvk::engine {

int device_type_rank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
  }
}

const char* device_type_name(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}

namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

std::string version_text(uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v));
}

std::string too_old(const DeviceCandidate& c, uint32_t min_api) {
  return "device '" + c.name + "' supports Vulkan " + version_text(c.api_version) + "; TressVK needs Vulkan " +
         version_text(min_api);
}

}  // namespace

DeviceChoice choose_device(std::span<const DeviceCandidate> candidates, std::string_view selector,
                           uint32_t min_api) {
  DeviceChoice choice;
  if (candidates.empty()) {
    choice.error = "no Vulkan device found (is a Vulkan driver installed? for lavapipe: mesa-vulkan-drivers)";
    return choice;
  }
  if (!selector.empty()) {
    std::optional<uint32_t> found;
    if (std::all_of(selector.begin(), selector.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      const unsigned long index = selector.size() > 9 ? candidates.size() : std::stoul(std::string(selector));
      if (index >= candidates.size()) {
        choice.error = "device index " + std::string(selector) + " is out of range (" +
                       std::to_string(candidates.size()) + " device(s); see --list-devices)";
        return choice;
      }
      found = static_cast<uint32_t>(index);
    } else {
      const std::string needle = lower(selector);
      for (uint32_t i = 0; i < candidates.size() && !found; ++i)
        if (lower(candidates[i].name).find(needle) != std::string::npos) found = i;
      if (!found) {
        choice.error = "no device name contains '" + std::string(selector) + "' (see --list-devices)";
        return choice;
      }
    }
    if (candidates[*found].api_version < min_api) {
      choice.error = too_old(candidates[*found], min_api);
      return choice;
    }
    choice.index = found;
    return choice;
  }
  for (uint32_t i = 0; i < candidates.size(); ++i) {
    if (candidates[i].api_version < min_api) continue;
    if (!choice.index ||
        device_type_rank(candidates[i].type) < device_type_rank(candidates[*choice.index].type))
      choice.index = i;
  }
  if (!choice.index) choice.error = too_old(candidates[0], min_api) + " (and no other device does)";
  return choice;
}

}  // namespace tressvk::engine
