#include "core/gpu.hpp"

namespace tressvk {
namespace {

// TRESSVK_DEBUG_ALLOCATIONS=1: every buffer's memory object and offset as an info message (read once per process), to
// relate a kernel's speed to where its buffers landed.
bool allocations_logged() {
  static const bool on = env_flag("TRESSVK_DEBUG_ALLOCATIONS");
  return on;
}

}  // namespace

TvkResult create_buffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, Memory memory, const char* name,
                        GpuBuffer& out) {
  out = GpuBuffer{};
  VkBufferCreateInfo bci{};
  bci.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  bci.size = size ? size : 16;  // zero-sized buffers are invalid; keep empty sections bindable
  bci.usage = usage;
  bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VmaAllocationCreateInfo aci{};
  aci.usage = VMA_MEMORY_USAGE_AUTO;
  switch (memory) {
    case Memory::device:
      aci.usage = VMA_MEMORY_USAGE_AUTO_PREFER_DEVICE;
      break;
    case Memory::host_upload:
      aci.flags = VMA_ALLOCATION_CREATE_HOST_ACCESS_SEQUENTIAL_WRITE_BIT | VMA_ALLOCATION_CREATE_MAPPED_BIT;
      break;
    case Memory::host_readback:
      aci.flags = VMA_ALLOCATION_CREATE_HOST_ACCESS_RANDOM_BIT | VMA_ALLOCATION_CREATE_MAPPED_BIT;
      aci.requiredFlags = VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      break;
  }
  VmaAllocationInfo info{};
  const VkResult vr = vmaCreateBuffer(ctx.allocator, &bci, &aci, &out.buffer, &out.allocation, &info);
  if (vr != VK_SUCCESS) {
    out = GpuBuffer{};
    return ctx.fail(vr == VK_ERROR_OUT_OF_DEVICE_MEMORY || vr == VK_ERROR_OUT_OF_HOST_MEMORY ? TVK_ERROR_OUT_OF_MEMORY
                                                                                             : TVK_ERROR_VULKAN,
                    "allocating %llu bytes for %s failed: %s", static_cast<unsigned long long>(bci.size), name,
                    vk_result_name(vr));
  }
  out.size = size;
  out.mapped = info.pMappedData;
  if (allocations_logged())
    ctx.message(TVK_MESSAGE_INFO, "allocation: %s, %llu bytes, memory %p at offset %llu", name,
                static_cast<unsigned long long>(bci.size), static_cast<void*>(info.deviceMemory),
                static_cast<unsigned long long>(info.offset));
  return TVK_SUCCESS;
}

void destroy_buffer(Context& ctx, GpuBuffer& buffer) {
  if (buffer.buffer) vmaDestroyBuffer(ctx.allocator, buffer.buffer, buffer.allocation);
  buffer = GpuBuffer{};
}

void destroy_buffer_deferred(Context& ctx, GpuBuffer& buffer) {
  if (buffer.buffer) ctx.deferred_buffers.push_back({ctx.frame, buffer.buffer, buffer.allocation});
  buffer = GpuBuffer{};
}

void Context::collect_garbage(bool everything) {
  size_t kept = 0;
  for (const DeferredBuffer& d : deferred_buffers) {
    if (everything || frame >= d.release_frame + frames_in_flight)
      vmaDestroyBuffer(allocator, d.buffer, d.allocation);
    else
      deferred_buffers[kept++] = d;
  }
  deferred_buffers.resize(kept);
  kept = 0;
  for (const DeferredPool& d : deferred_pools) {
    if (everything || frame >= d.release_frame + frames_in_flight)
      vk.vkDestroyDescriptorPool(info.device, d.pool, info.allocator);
    else
      deferred_pools[kept++] = d;
  }
  deferred_pools.resize(kept);
}

}  // namespace tressvk
