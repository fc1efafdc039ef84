// The doubling compute shader (tests/engine/shaders/double.comp) as a ready pipeline with one storage-buffer set.
#pragma once

#include <tressvk/engine/descriptors.hpp>
#include <tressvk/engine/pipeline.hpp>
#include <tressvk/test/vulkan.hpp>

#include "tressvk_engine_test_spirv.h"

namespace tressvk::test {

struct DoublePipeline {
  static constexpr uint32_t kGroupSize = 64;

  engine::DeviceHandle<VkDescriptorSetLayout> set_layout;
  engine::DescriptorPool pool;
  engine::Pipeline pipeline;

  DoublePipeline() {
    engine::Device& dev = device();
    set_layout = engine::create_set_layout(dev, {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}});
    pool = engine::DescriptorPool(dev, 4);
    engine::ComputePipelineDesc desc;
    desc.spirv = k_spv_double_comp;
    desc.spec_constants = {{0, kGroupSize}};
    desc.layout.set_layouts = {set_layout.get()};
    desc.layout.push_constant_size = sizeof(uint32_t);
    desc.debug_name = "test double";
    pipeline = engine::create_compute_pipeline(dev, desc);
  }

  VkDescriptorSet set_for(const engine::Buffer& buffer) const {
    VkDescriptorSet set = pool.allocate(set_layout);
    engine::write_buffer_descriptor(device(), set, 0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, buffer.handle());
    return set;
  }

  void cmd_dispatch(VkCommandBuffer cmd, VkDescriptorSet set, uint32_t count) const {
    pipeline.cmd_bind(cmd);
    pipeline.cmd_bind_set(cmd, 0, set);
    pipeline.cmd_push(cmd, count);
    vkCmdDispatch(cmd, engine::group_count(count, kGroupSize), 1, 1);
  }
};

}  // namespace tressvk::test
