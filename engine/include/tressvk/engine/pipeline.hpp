// Pipeline helpers: SPIR-V words in, pipeline + layout out. Graphics pipelines are built for dynamic rendering
// (attachment formats given), with viewport and scissor dynamic. Specialization constants are 32-bit values.
#pragma once

#include <tressvk/engine/device.hpp>
#include <tressvk/engine/handle.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace tressvk::engine {

struct SpecConstant {
  uint32_t id = 0;
  uint32_t value = 0;  // a uint/int/bool(0 or 1) constant, or a float's bits (std::bit_cast)
};

struct PipelineLayoutDesc {
  std::vector<VkDescriptorSetLayout> set_layouts;
  uint32_t push_constant_size = 0;  // bytes, visible to every stage of the pipeline; keep <= 128
};

class Pipeline {
 public:
  Pipeline() = default;
  Pipeline(DeviceHandle<VkPipelineLayout> layout, DeviceHandle<VkPipeline> pipeline, VkPipelineBindPoint point,
           VkShaderStageFlags push_stages)
      : layout_(std::move(layout)), pipeline_(std::move(pipeline)), bind_point_(point), push_stages_(push_stages) {}

  VkPipeline handle() const { return pipeline_.get(); }
  VkPipelineLayout layout() const { return layout_.get(); }
  VkPipelineBindPoint bind_point() const { return bind_point_; }
  explicit operator bool() const { return static_cast<bool>(pipeline_); }

  void cmd_bind(VkCommandBuffer cmd) const;
  void cmd_push_constants(VkCommandBuffer cmd, const void* data, uint32_t size, uint32_t offset = 0) const;
  template <typename T>
  void cmd_push(VkCommandBuffer cmd, const T& value) const {
    cmd_push_constants(cmd, &value, static_cast<uint32_t>(sizeof(T)));
  }
  void cmd_bind_set(VkCommandBuffer cmd, uint32_t set_index, VkDescriptorSet set) const;

 private:
  DeviceHandle<VkPipelineLayout> layout_;  // destroyed after the pipeline (members destroy in reverse order)
  DeviceHandle<VkPipeline> pipeline_;
  VkPipelineBindPoint bind_point_ = VK_PIPELINE_BIND_POINT_GRAPHICS;
  VkShaderStageFlags push_stages_ = 0;
};

struct ComputePipelineDesc {
  std::span<const uint32_t> spirv;
  const char* entry = "main";
  std::vector<SpecConstant> spec_constants;
  PipelineLayoutDesc layout;
  const char* debug_name = nullptr;
};

struct GraphicsPipelineDesc {
  std::span<const uint32_t> vertex_spirv;
  std::span<const uint32_t> fragment_spirv;  // may be empty for depth-only passes (shadow maps)
  std::vector<SpecConstant> spec_constants;   // given to both stages
  PipelineLayoutDesc layout;
  std::vector<VkFormat> color_formats;        // attachment formats (one blend state per colour attachment)
  VkFormat depth_format = VK_FORMAT_UNDEFINED;
  // VK_NULL_HANDLE: built for dynamic rendering with the formats above. Otherwise: for this render pass and
  // subpass (the formats must still describe its attachments).
  VkRenderPass render_pass = VK_NULL_HANDLE;
  uint32_t subpass = 0;
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkCullModeFlags cull_mode = VK_CULL_MODE_NONE;
  VkFrontFace front_face = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  bool depth_test = true;
  bool depth_write = true;
  VkCompareOp depth_compare = VK_COMPARE_OP_LESS_OR_EQUAL;
  bool depth_bias = false;   // when true, depth bias is dynamic state (vkCmdSetDepthBias)
  bool alpha_blend = false;  // premultiplied-alpha "over" blending on every colour attachment
  const char* debug_name = nullptr;
};

DeviceHandle<VkPipelineLayout> create_pipeline_layout(const Device& device, const PipelineLayoutDesc& desc,
                                                      VkShaderStageFlags push_stages);
Pipeline create_compute_pipeline(const Device& device, const ComputePipelineDesc& desc);
Pipeline create_graphics_pipeline(const Device& device, const GraphicsPipelineDesc& desc);

// Group count covering `items` with groups of `group_size` (ceil division).
inline uint32_t group_count(uint32_t items, uint32_t group_size) { return (items + group_size - 1) / group_size; }

}  // namespace tressvk::engine
