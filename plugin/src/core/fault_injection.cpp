// The fault-injection wrappers of fault_injection.hpp.
#include "core/fault_injection.hpp"

namespace tressvk::fault {
namespace {

VolkDeviceTable g_real{};
Control* g_control = nullptr;

// Counts one fallible call; true when it is the one to fail.
bool fail_now(const char* name) {
  if (!g_control) return false;
  const uint64_t n = ++g_control->calls;
  if (g_control->fail_at != 0 && n == g_control->fail_at) {
    g_control->fired = name;
    return true;
  }
  return false;
}

#define TVK_WRAP(name, error, params, args)                        \
  VKAPI_ATTR VkResult VKAPI_CALL wrap_##name params {              \
    if (fail_now(#name)) return error;                             \
    return g_real.name args;                                       \
  }

TVK_WRAP(vkAllocateMemory, VK_ERROR_OUT_OF_DEVICE_MEMORY,
         (VkDevice d, const VkMemoryAllocateInfo* i, const VkAllocationCallbacks* a, VkDeviceMemory* m), (d, i, a, m))
TVK_WRAP(vkMapMemory, VK_ERROR_MEMORY_MAP_FAILED,
         (VkDevice d, VkDeviceMemory m, VkDeviceSize o, VkDeviceSize s, VkMemoryMapFlags f, void** p), (d, m, o, s, f, p))
TVK_WRAP(vkBindBufferMemory, VK_ERROR_OUT_OF_DEVICE_MEMORY, (VkDevice d, VkBuffer b, VkDeviceMemory m, VkDeviceSize o),
         (d, b, m, o))
TVK_WRAP(vkBindBufferMemory2, VK_ERROR_OUT_OF_DEVICE_MEMORY,
         (VkDevice d, uint32_t n, const VkBindBufferMemoryInfo* i), (d, n, i))
TVK_WRAP(vkBindImageMemory, VK_ERROR_OUT_OF_DEVICE_MEMORY, (VkDevice d, VkImage b, VkDeviceMemory m, VkDeviceSize o),
         (d, b, m, o))
TVK_WRAP(vkBindImageMemory2, VK_ERROR_OUT_OF_DEVICE_MEMORY,
         (VkDevice d, uint32_t n, const VkBindImageMemoryInfo* i), (d, n, i))
TVK_WRAP(vkCreateBuffer, VK_ERROR_OUT_OF_HOST_MEMORY,
         (VkDevice d, const VkBufferCreateInfo* i, const VkAllocationCallbacks* a, VkBuffer* o), (d, i, a, o))
TVK_WRAP(vkCreateImage, VK_ERROR_OUT_OF_HOST_MEMORY,
         (VkDevice d, const VkImageCreateInfo* i, const VkAllocationCallbacks* a, VkImage* o), (d, i, a, o))
TVK_WRAP(vkCreateDescriptorPool, VK_ERROR_OUT_OF_HOST_MEMORY,
         (VkDevice d, const VkDescriptorPoolCreateInfo* i, const VkAllocationCallbacks* a, VkDescriptorPool* o),
         (d, i, a, o))
TVK_WRAP(vkAllocateDescriptorSets, VK_ERROR_OUT_OF_POOL_MEMORY,
         (VkDevice d, const VkDescriptorSetAllocateInfo* i, VkDescriptorSet* o), (d, i, o))
TVK_WRAP(vkCreateDescriptorSetLayout, VK_ERROR_OUT_OF_HOST_MEMORY,
         (VkDevice d, const VkDescriptorSetLayoutCreateInfo* i, const VkAllocationCallbacks* a,
          VkDescriptorSetLayout* o),
         (d, i, a, o))
TVK_WRAP(vkCreatePipelineLayout, VK_ERROR_OUT_OF_HOST_MEMORY,
         (VkDevice d, const VkPipelineLayoutCreateInfo* i, const VkAllocationCallbacks* a, VkPipelineLayout* o),
         (d, i, a, o))
TVK_WRAP(vkCreateShaderModule, VK_ERROR_OUT_OF_HOST_MEMORY,
         (VkDevice d, const VkShaderModuleCreateInfo* i, const VkAllocationCallbacks* a, VkShaderModule* o),
         (d, i, a, o))
TVK_WRAP(vkCreateQueryPool, VK_ERROR_OUT_OF_HOST_MEMORY,
         (VkDevice d, const VkQueryPoolCreateInfo* i, const VkAllocationCallbacks* a, VkQueryPool* o), (d, i, a, o))
TVK_WRAP(vkFlushMappedMemoryRanges, VK_ERROR_OUT_OF_HOST_MEMORY, (VkDevice d, uint32_t n, const VkMappedMemoryRange* r),
         (d, n, r))
TVK_WRAP(vkInvalidateMappedMemoryRanges, VK_ERROR_OUT_OF_HOST_MEMORY,
         (VkDevice d, uint32_t n, const VkMappedMemoryRange* r), (d, n, r))

#undef TVK_WRAP

// Pipeline creation fails with every output handle set to VK_NULL_HANDLE, as the specification requires.
template <typename CreateInfo>
VkResult create_pipelines(const char* name,
                          VkResult(VKAPI_PTR* real)(VkDevice, VkPipelineCache, uint32_t, const CreateInfo*,
                                                    const VkAllocationCallbacks*, VkPipeline*),
                          VkDevice d, VkPipelineCache c, uint32_t n, const CreateInfo* i, const VkAllocationCallbacks* a,
                          VkPipeline* o) {
  if (fail_now(name)) {
    for (uint32_t k = 0; k < n; ++k) o[k] = VK_NULL_HANDLE;
    return VK_ERROR_OUT_OF_HOST_MEMORY;
  }
  return real(d, c, n, i, a, o);
}
VKAPI_ATTR VkResult VKAPI_CALL wrap_vkCreateComputePipelines(VkDevice d, VkPipelineCache c, uint32_t n,
                                                             const VkComputePipelineCreateInfo* i,
                                                             const VkAllocationCallbacks* a, VkPipeline* o) {
  return create_pipelines("vkCreateComputePipelines", g_real.vkCreateComputePipelines, d, c, n, i, a, o);
}
VKAPI_ATTR VkResult VKAPI_CALL wrap_vkCreateGraphicsPipelines(VkDevice d, VkPipelineCache c, uint32_t n,
                                                              const VkGraphicsPipelineCreateInfo* i,
                                                              const VkAllocationCallbacks* a, VkPipeline* o) {
  return create_pipelines("vkCreateGraphicsPipelines", g_real.vkCreateGraphicsPipelines, d, c, n, i, a, o);
}

// A lost device is not a counted fault: once `device_lost` is set the device stays lost, as a real one does.
VKAPI_ATTR VkResult VKAPI_CALL wrap_vkGetQueryPoolResults(VkDevice d, VkQueryPool p, uint32_t first, uint32_t count,
                                                          size_t size, void* data, VkDeviceSize stride,
                                                          VkQueryResultFlags flags) {
  if (g_control && g_control->device_lost) return VK_ERROR_DEVICE_LOST;
  return g_real.vkGetQueryPoolResults(d, p, first, count, size, data, stride, flags);
}

}  // namespace

void install(const void* next, VolkDeviceTable& t) {
  const auto* link = static_cast<const ChainLink*>(next);
  while (link && link->type != kChainType) link = static_cast<const ChainLink*>(link->next);
  if (!link || !link->control) return;
  g_control = link->control;
  g_real = t;
#define TVK_SET(name) t.name = wrap_##name
  TVK_SET(vkAllocateMemory);
  TVK_SET(vkMapMemory);
  TVK_SET(vkBindBufferMemory);
  TVK_SET(vkBindBufferMemory2);
  TVK_SET(vkBindImageMemory);
  TVK_SET(vkBindImageMemory2);
  TVK_SET(vkCreateBuffer);
  TVK_SET(vkCreateImage);
  TVK_SET(vkCreateDescriptorPool);
  TVK_SET(vkAllocateDescriptorSets);
  TVK_SET(vkCreateDescriptorSetLayout);
  TVK_SET(vkCreatePipelineLayout);
  TVK_SET(vkCreateShaderModule);
  TVK_SET(vkCreateQueryPool);
  TVK_SET(vkFlushMappedMemoryRanges);
  TVK_SET(vkInvalidateMappedMemoryRanges);
  TVK_SET(vkCreateComputePipelines);
  TVK_SET(vkCreateGraphicsPipelines);
  TVK_SET(vkGetQueryPoolResults);
#undef TVK_SET
}

}  // namespace tressvk::fault

