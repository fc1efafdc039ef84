#include <tressvk/engine/descriptors.hpp>

namespace tressvk::engine {

DeviceHandle<VkDescriptorSetLayout> create_set_layout(const Device& device, const std::vector<Binding>& bindings) {
  std::vector<VkDescriptorSetLayoutBinding> vk_bindings;
  for (const Binding& b : bindings) vk_bindings.push_back({b.binding, b.type, b.count, b.stages, nullptr});
  VkDescriptorSetLayoutCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  info.bindingCount = static_cast<uint32_t>(vk_bindings.size());
  info.pBindings = vk_bindings.data();
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  vk_check(vkCreateDescriptorSetLayout(device.device(), &info, nullptr, &layout), "vkCreateDescriptorSetLayout");
  return DeviceHandle<VkDescriptorSetLayout>(device.device(), layout, vkDestroyDescriptorSetLayout);
}

DescriptorPool::DescriptorPool(const Device& device, uint32_t max_sets, uint32_t descriptors_per_type)
    : device_(device.device()) {
  const VkDescriptorPoolSize sizes[] = {
      {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, descriptors_per_type},
      {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, descriptors_per_type},
      {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, descriptors_per_type},
      {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, descriptors_per_type},
  };
  VkDescriptorPoolCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  info.maxSets = max_sets;
  info.poolSizeCount = static_cast<uint32_t>(std::size(sizes));
  info.pPoolSizes = sizes;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  vk_check(vkCreateDescriptorPool(device_, &info, nullptr, &pool), "vkCreateDescriptorPool");
  pool_ = DeviceHandle<VkDescriptorPool>(device_, pool, vkDestroyDescriptorPool);
}

VkDescriptorSet DescriptorPool::allocate(VkDescriptorSetLayout layout) const {
  VkDescriptorSetAllocateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  info.descriptorPool = pool_;
  info.descriptorSetCount = 1;
  info.pSetLayouts = &layout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  vk_check(vkAllocateDescriptorSets(device_, &info, &set), "vkAllocateDescriptorSets");
  return set;
}

DeviceHandle<VkSampler> create_sampler(const Device& device, const SamplerDesc& desc) {
  VkSamplerCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
  info.magFilter = desc.filter;
  info.minFilter = desc.filter;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  info.addressModeU = desc.address;
  info.addressModeV = desc.address;
  info.addressModeW = desc.address;
  info.borderColor = desc.border;
  info.compareEnable = desc.compare ? VK_TRUE : VK_FALSE;
  info.compareOp = desc.compare_op;
  info.maxLod = VK_LOD_CLAMP_NONE;
  const float limit = device.properties().limits.maxSamplerAnisotropy;
  if (desc.max_anisotropy > 1.0f && device.sampler_anisotropy()) {
    info.anisotropyEnable = VK_TRUE;
    info.maxAnisotropy = desc.max_anisotropy < limit ? desc.max_anisotropy : limit;
  }
  VkSampler sampler = VK_NULL_HANDLE;
  vk_check(vkCreateSampler(device.device(), &info, nullptr, &sampler), "vkCreateSampler");
  return DeviceHandle<VkSampler>(device.device(), sampler, vkDestroySampler);
}

namespace {

// One descriptor of `set` at `binding`, from a buffer or an image (the other pointer null).
void write_descriptor(const Device& device, VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
                      const VkDescriptorBufferInfo* buffer, const VkDescriptorImageInfo* image) {
  VkWriteDescriptorSet write{};
  write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
  write.dstSet = set;
  write.dstBinding = binding;
  write.descriptorCount = 1;
  write.descriptorType = type;
  write.pBufferInfo = buffer;
  write.pImageInfo = image;
  vkUpdateDescriptorSets(device.device(), 1, &write, 0, nullptr);
}

}  // namespace

void write_buffer_descriptor(const Device& device, VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
                             VkBuffer buffer, VkDeviceSize offset, VkDeviceSize range) {
  const VkDescriptorBufferInfo buffer_info{buffer, offset, range};
  write_descriptor(device, set, binding, type, &buffer_info, nullptr);
}

void write_image_descriptor(const Device& device, VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
                            VkImageView view, VkImageLayout layout, VkSampler sampler) {
  const VkDescriptorImageInfo image_info{sampler, view, layout};
  write_descriptor(device, set, binding, type, nullptr, &image_info);
}

}  // namespace tressvk::engine
