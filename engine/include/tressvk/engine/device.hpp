// The engine's Vulkan foundation: instance, debug messenger, physical device choice, logical device, one queue,
// a VMA allocator and a command pool for one-shot work. One Device per process (volk's global function pointers
// are loaded for it); the plugin keeps its own function table and never touches these globals.
#pragma once

#include <tressvk/engine/check.hpp>
#include <tressvk/engine/device_select.hpp>
#include <tressvk/engine/messenger.hpp>

#include <volk.h>
#include <vk_mem_alloc.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace tressvk::engine {

// What a plugin needs of the device, merged in before vkCreateDevice (tressvk::host::with_plugin_requirements
// fills it from tressvk_get_device_requirements); a missing feature or extension is an error naming it.
struct DeviceRequirements {
  uint32_t min_api_version = 0;
  std::vector<std::string> extensions;
  bool synchronization2 = false;
  bool dynamic_rendering = false;
};

struct DeviceOptions {
  std::string app_name = "tressvk";
  // Device index or case-insensitive name substring; empty: the environment variable TRESSVK_DEVICE if set,
  // else automatic (discrete, integrated, virtual, then CPU devices such as lavapipe).
  std::string device;
  bool validation = false;       // enable VK_LAYER_KHRONOS_validation (an error if it is not installed)
  bool sync_validation = false;  // also synchronization validation (implies validation)
  bool print_messages = true;    // print validation messages to stderr as they arrive
  // Windowed hosts (tressvk-viewer): the window system's instance extensions (e.g. from
  // glfwGetRequiredInstanceExtensions) and a function that makes the window's surface once the instance exists.
  // With create_surface set the Device owns the surface, enables VK_KHR_swapchain and picks a queue family that
  // can also present to it. Left empty (the default) the device stays headless: no surface, no swapchain.
  std::vector<std::string> instance_extensions;
  std::function<VkSurfaceKHR(VkInstance)> create_surface;
  DeviceRequirements requirements;  // the plugin's (see tressvk::host::with_plugin_requirements)
};

// A device as listed by list_devices().
struct DeviceInfo {
  uint32_t index = 0;
  std::string name;
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  uint32_t api_version = 0;
  std::string driver;  // driverName + driverInfo
};

// Enumerates the devices the loader offers (creates and destroys a bare instance).
std::vector<DeviceInfo> list_devices();
std::string api_version_string(uint32_t version);

// A diagnostic switch from the environment: set, and not "0".
bool env_flag(const char* name);
// TRESSVK_PIPELINE_STATS is set (and not "0"): the device enables VK_KHR_pipeline_executable_properties where
// offered, and the tools print the plugin's messages, among them its pipelines' compiler statistics.
bool pipeline_stats_requested();

class Device {
 public:
  explicit Device(const DeviceOptions& options);
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physical_device() const { return physical_device_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }  // graphics + compute (+ present on a windowed device)
  VkSurfaceKHR surface() const { return surface_; }  // VK_NULL_HANDLE on a headless device
  uint32_t queue_family() const { return queue_family_; }
  VmaAllocator allocator() const { return allocator_; }
  uint32_t api_version() const { return api_version_; }  // what the instance and device were created for
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  const char* name() const { return properties_.deviceName; }
  std::string description() const;  // "name (type, Vulkan x.y.z, driver)"

  bool validation_enabled() const { return validation_; }
  bool sync_validation_enabled() const { return sync_validation_; }
  MessageLog& messages() { return *log_; }
  const MessageLog& messages() const { return *log_; }
  // Shared so the count can still be read after the Device (and its instance) is destroyed, which is when
  // leak reports arrive.
  std::shared_ptr<MessageLog> message_log() const { return log_; }

  // Optional features the engine enabled because the device has them.
  bool sampler_anisotropy() const { return sampler_anisotropy_; }
  bool depth_clamp() const { return depth_clamp_; }

  // Timestamps: supported when the queue family has timestampValidBits > 0.
  bool timestamps_supported() const { return timestamp_valid_bits_ > 0; }
  uint32_t timestamp_valid_bits() const { return timestamp_valid_bits_; }
  double timestamp_period_ns() const { return properties_.limits.timestampPeriod; }

  // Records `record` into a fresh primary command buffer, submits it and waits for it on a fence.
  void run_commands(const std::function<void(VkCommandBuffer)>& record) const;
  void wait_idle() const;

  // Debug name for a Vulkan object (shows in validation messages); a no-op without VK_EXT_debug_utils.
  void set_name(VkObjectType type, uint64_t handle, const char* name) const;

 private:
  void create_instance(const DeviceOptions& options);
  void pick_physical_device(const DeviceOptions& options);
  void create_device();
  void create_allocator();
  void release();

  std::shared_ptr<MessageLog> log_;  // first member: outlives the instance it listens to
  bool validation_ = false;
  bool sync_validation_ = false;
  bool debug_utils_ = false;
  uint32_t api_version_ = VK_API_VERSION_1_3;
  DeviceRequirements requirements_;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties_{};
  VkDevice device_ = VK_NULL_HANDLE;
  uint32_t queue_family_ = 0;
  uint32_t timestamp_valid_bits_ = 0;
  bool sampler_anisotropy_ = false;
  bool depth_clamp_ = false;
  VkQueue queue_ = VK_NULL_HANDLE;
  VmaAllocator allocator_ = VK_NULL_HANDLE;
  VkCommandPool command_pool_ = VK_NULL_HANDLE;
};

}  // namespace tressvk::engine
