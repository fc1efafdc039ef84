// RAII buffers allocated with VMA, and host upload/readback helpers.
#pragma once

#include <tressvk/engine/device.hpp>

#include <cstddef>
#include <cstring>
#include <span>
#include <vector>

namespace tressvk::engine {

enum class MemoryUsage {
  device_local,  // GPU memory; host access goes through a staging buffer (TRANSFER_SRC|DST are added)
  upload,        // host-visible, persistently mapped, written sequentially by the host
  readback,      // host-visible, persistently mapped, cached for host reads
};

class Buffer {
 public:
  Buffer() = default;
  Buffer(VmaAllocator allocator, const VkBufferCreateInfo& info, MemoryUsage usage);
  ~Buffer() { reset(); }
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  MemoryUsage usage() const { return usage_; }
  void* mapped() const { return mapped_; }  // non-null for upload/readback buffers
  VmaAllocator allocator() const { return allocator_; }
  VmaAllocation allocation() const { return allocation_; }
  explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }
  void reset();

 private:
  VmaAllocator allocator_ = VK_NULL_HANDLE;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VmaAllocation allocation_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  MemoryUsage usage_ = MemoryUsage::device_local;
  void* mapped_ = nullptr;
};

Buffer create_buffer(const Device& device, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory);

// Host → buffer. Mapped buffers: memcpy + flush. Device-local buffers: a staging copy submitted and waited for,
// followed by a barrier that makes the copy visible to all later commands.
void write_buffer(const Device& device, const Buffer& buffer, std::span<const std::byte> data,
                  VkDeviceSize offset = 0);
// Buffer → host. Waits for the device: first a barrier that makes all earlier writes visible (to the copy or to
// the host), then a copy through a staging buffer for device-local memory.
void read_buffer(const Device& device, const Buffer& buffer, std::span<std::byte> out, VkDeviceSize offset = 0);

template <typename T>
Buffer create_buffer_with_data(const Device& device, std::span<const T> data, VkBufferUsageFlags usage,
                               MemoryUsage memory = MemoryUsage::device_local) {
  Buffer buffer = create_buffer(device, data.size_bytes(), usage, memory);
  write_buffer(device, buffer, std::as_bytes(data));
  return buffer;
}

template <typename T>
std::vector<T> read_buffer_as(const Device& device, const Buffer& buffer, size_t count, VkDeviceSize offset = 0) {
  std::vector<T> out(count);
  read_buffer(device, buffer, std::as_writable_bytes(std::span<T>(out)), offset);
  return out;
}

}  // namespace tressvk::engine
