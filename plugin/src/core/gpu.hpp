// GPU resources owned by TressVK: buffers allocated from the context's private VMA allocator, and destruction
// deferred until the GPU can no longer be using them.
#pragma once

#include "core/context.hpp"

#include <cstdint>

namespace tressvk {

struct GpuBuffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VmaAllocation allocation = VK_NULL_HANDLE;
  VkDeviceSize size = 0;
  void* mapped = nullptr;  // host-visible buffers only
  explicit operator bool() const { return buffer != VK_NULL_HANDLE; }
};

enum class Memory { device, host_upload, host_readback };

// Creates a buffer; on failure records the error on the context and returns it.
TvkResult create_buffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, Memory memory, const char* name,
                        GpuBuffer& out);
void destroy_buffer(Context& ctx, GpuBuffer& buffer);
// Destroys the buffer once `frames_in_flight` more frames have been recorded (see Context::advance_frame).
void destroy_buffer_deferred(Context& ctx, GpuBuffer& buffer);

}  // namespace tressvk
