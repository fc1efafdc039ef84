// Minimal descriptor helpers: a set layout from bindings, a pool that hands out sets, buffer/image writes.
#pragma once

#include <tressvk/engine/device.hpp>
#include <tressvk/engine/handle.hpp>

#include <vector>

namespace tressvk::engine {

struct Binding {
  uint32_t binding = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  VkShaderStageFlags stages = VK_SHADER_STAGE_ALL;
  uint32_t count = 1;
};

DeviceHandle<VkDescriptorSetLayout> create_set_layout(const Device& device, const std::vector<Binding>& bindings);

// A pool sized for `max_sets` sets of up to `descriptors_per_type` descriptors of each common type. Sets are
// freed together with the pool.
class DescriptorPool {
 public:
  DescriptorPool() = default;
  DescriptorPool(const Device& device, uint32_t max_sets, uint32_t descriptors_per_type = 16);
  VkDescriptorSet allocate(VkDescriptorSetLayout layout) const;

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  DeviceHandle<VkDescriptorPool> pool_;
};

struct SamplerDesc {
  VkFilter filter = VK_FILTER_LINEAR;
  VkSamplerAddressMode address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  VkBorderColor border = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;  // with CLAMP_TO_BORDER: "lit" outside a shadow map
  bool compare = false;  // depth comparison (shadow maps: sampler2DShadow), with compare_op
  VkCompareOp compare_op = VK_COMPARE_OP_LESS_OR_EQUAL;
  float max_anisotropy = 1.0f;  // > 1 only when the device enabled samplerAnisotropy; clamped to its limit
};
DeviceHandle<VkSampler> create_sampler(const Device& device, const SamplerDesc& desc = {});

void write_buffer_descriptor(const Device& device, VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
                             VkBuffer buffer, VkDeviceSize offset = 0, VkDeviceSize range = VK_WHOLE_SIZE);
void write_image_descriptor(const Device& device, VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
                            VkImageView view, VkImageLayout layout, VkSampler sampler = VK_NULL_HANDLE);

}  // namespace tressvk::engine
