// A move-only owner for a device-level Vulkan handle (pipeline, layout, pool...). The destroy function is
// captured at construction (volk's pointers are loaded by then), so one template serves every handle type.
#pragma once

#include <volk.h>

#include <utility>

namespace tressvk::engine {

template <typename T>
class DeviceHandle {
 public:
  using Destroy = void (*)(VkDevice, T, const VkAllocationCallbacks*);

  DeviceHandle() = default;
  DeviceHandle(VkDevice device, T handle, Destroy destroy) : device_(device), handle_(handle), destroy_(destroy) {}
  ~DeviceHandle() { reset(); }
  DeviceHandle(DeviceHandle&& other) noexcept
      : device_(other.device_), handle_(std::exchange(other.handle_, T{})), destroy_(other.destroy_) {}
  DeviceHandle& operator=(DeviceHandle&& other) noexcept {
    if (this != &other) {
      reset();
      device_ = other.device_;
      handle_ = std::exchange(other.handle_, T{});
      destroy_ = other.destroy_;
    }
    return *this;
  }
  DeviceHandle(const DeviceHandle&) = delete;
  DeviceHandle& operator=(const DeviceHandle&) = delete;

  T get() const { return handle_; }
  operator T() const { return handle_; }  // NOLINT: handles are passed to Vulkan calls directly
  explicit operator bool() const { return handle_ != T{}; }
  void reset() {
    if (handle_ != T{} && destroy_) destroy_(device_, handle_, nullptr);
    handle_ = T{};
  }

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  T handle_{};
  Destroy destroy_ = nullptr;
};

}  // namespace tressvk::engine
