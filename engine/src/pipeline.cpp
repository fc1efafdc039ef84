#include <tressvk/engine/pipeline.hpp>

#include <vector>

namespace tressvk::engine {

namespace {

DeviceHandle<VkShaderModule> create_module(const Device& device, std::span<const uint32_t> spirv) {
  if (spirv.empty()) throw Error("pipeline: empty SPIR-V");
  VkShaderModuleCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  info.codeSize = spirv.size_bytes();
  info.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  vk_check(vkCreateShaderModule(device.device(), &info, nullptr, &module), "vkCreateShaderModule");
  return DeviceHandle<VkShaderModule>(device.device(), module, vkDestroyShaderModule);
}

// Specialization data for a list of 32-bit constants; the entries point into `values`, so keep both alive.
struct Specialization {
  std::vector<VkSpecializationMapEntry> entries;
  std::vector<uint32_t> values;
  VkSpecializationInfo info{};

  explicit Specialization(const std::vector<SpecConstant>& constants) {
    for (const SpecConstant& c : constants) {
      entries.push_back({c.id, static_cast<uint32_t>(values.size() * sizeof(uint32_t)), sizeof(uint32_t)});
      values.push_back(c.value);
    }
    info.mapEntryCount = static_cast<uint32_t>(entries.size());
    info.pMapEntries = entries.data();
    info.dataSize = values.size() * sizeof(uint32_t);
    info.pData = values.data();
  }
  const VkSpecializationInfo* get() const { return entries.empty() ? nullptr : &info; }
};

}  // namespace

DeviceHandle<VkPipelineLayout> create_pipeline_layout(const Device& device, const PipelineLayoutDesc& desc,
                                                      VkShaderStageFlags push_stages) {
  const VkPushConstantRange range{push_stages, 0, desc.push_constant_size};
  VkPipelineLayoutCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  info.setLayoutCount = static_cast<uint32_t>(desc.set_layouts.size());
  info.pSetLayouts = desc.set_layouts.data();
  info.pushConstantRangeCount = desc.push_constant_size ? 1 : 0;
  info.pPushConstantRanges = &range;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  vk_check(vkCreatePipelineLayout(device.device(), &info, nullptr, &layout), "vkCreatePipelineLayout");
  return DeviceHandle<VkPipelineLayout>(device.device(), layout, vkDestroyPipelineLayout);
}

void Pipeline::cmd_bind(VkCommandBuffer cmd) const { vkCmdBindPipeline(cmd, bind_point_, pipeline_); }

void Pipeline::cmd_push_constants(VkCommandBuffer cmd, const void* data, uint32_t size, uint32_t offset) const {
  vkCmdPushConstants(cmd, layout_, push_stages_, offset, size, data);
}

void Pipeline::cmd_bind_set(VkCommandBuffer cmd, uint32_t set_index, VkDescriptorSet set) const {
  vkCmdBindDescriptorSets(cmd, bind_point_, layout_, set_index, 1, &set, 0, nullptr);
}

namespace {

// Names a freshly created pipeline for the debug tools and wraps it with its layout.
Pipeline named_pipeline(const Device& device, VkPipeline pipeline, DeviceHandle<VkPipelineLayout> layout,
                        const char* debug_name, VkPipelineBindPoint bind_point, VkShaderStageFlags push_stages) {
  device.set_name(VK_OBJECT_TYPE_PIPELINE, reinterpret_cast<uint64_t>(pipeline), debug_name);
  return Pipeline(std::move(layout), DeviceHandle<VkPipeline>(device.device(), pipeline, vkDestroyPipeline),
                  bind_point, push_stages);
}

// out = src + dst * (1 - src.alpha) for colour and alpha (premultiplied "over").
constexpr VkPipelineColorBlendAttachmentState kPremultipliedOver{
    VK_TRUE,
    VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA, VK_BLEND_OP_ADD,
    VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA, VK_BLEND_OP_ADD,
    VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT};

}  // namespace

Pipeline create_compute_pipeline(const Device& device, const ComputePipelineDesc& desc) {
  auto module = create_module(device, desc.spirv);
  auto layout = create_pipeline_layout(device, desc.layout, VK_SHADER_STAGE_COMPUTE_BIT);
  const Specialization spec(desc.spec_constants);
  VkComputePipelineCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  info.stage = {};
  info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = desc.entry;
  info.stage.pSpecializationInfo = spec.get();
  info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  vk_check(vkCreateComputePipelines(device.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
           "vkCreateComputePipelines");
  return named_pipeline(device, pipeline, std::move(layout), desc.debug_name, VK_PIPELINE_BIND_POINT_COMPUTE,
                        VK_SHADER_STAGE_COMPUTE_BIT);
}

Pipeline create_graphics_pipeline(const Device& device, const GraphicsPipelineDesc& desc) {
  const bool has_fragment = !desc.fragment_spirv.empty();
  VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT;
  if (has_fragment) stages |= VK_SHADER_STAGE_FRAGMENT_BIT;
  auto vertex = create_module(device, desc.vertex_spirv);
  DeviceHandle<VkShaderModule> fragment;
  if (has_fragment) fragment = create_module(device, desc.fragment_spirv);
  auto layout = create_pipeline_layout(device, desc.layout, stages);
  const Specialization spec(desc.spec_constants);

  VkPipelineShaderStageCreateInfo stage_info[2]{};
  stage_info[0] = {};
  stage_info[0].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  stage_info[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stage_info[0].module = vertex;
  stage_info[0].pName = "main";
  stage_info[0].pSpecializationInfo = spec.get();
  stage_info[1] = stage_info[0];
  stage_info[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stage_info[1].module = fragment;

  // No vertex buffers: geometry comes from storage buffers or push constants (the hair draws work that way too).
  VkPipelineVertexInputStateCreateInfo vertex_input{};
  vertex_input.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
  VkPipelineInputAssemblyStateCreateInfo assembly{};
  assembly.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
  assembly.topology = desc.topology;
  VkPipelineViewportStateCreateInfo viewport{};
  viewport.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{};
  raster.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = desc.cull_mode;
  raster.frontFace = desc.front_face;
  raster.depthBiasEnable = desc.depth_bias ? VK_TRUE : VK_FALSE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{};
  multisample.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
  multisample.rasterizationSamples = desc.samples;
  VkPipelineDepthStencilStateCreateInfo depth{};
  depth.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
  const bool has_depth = desc.depth_format != VK_FORMAT_UNDEFINED;
  depth.depthTestEnable = has_depth && desc.depth_test ? VK_TRUE : VK_FALSE;
  depth.depthWriteEnable = has_depth && desc.depth_write ? VK_TRUE : VK_FALSE;
  depth.depthCompareOp = desc.depth_compare;

  std::vector<VkPipelineColorBlendAttachmentState> blend(desc.color_formats.size());
  for (auto& b : blend) {
    b = kPremultipliedOver;
    if (!desc.alpha_blend) b.blendEnable = VK_FALSE;
  }
  VkPipelineColorBlendStateCreateInfo color_blend{};
  color_blend.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
  color_blend.attachmentCount = static_cast<uint32_t>(blend.size());
  color_blend.pAttachments = blend.data();

  std::vector<VkDynamicState> dynamic = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  if (desc.depth_bias) dynamic.push_back(VK_DYNAMIC_STATE_DEPTH_BIAS);
  VkPipelineDynamicStateCreateInfo dynamic_state{};
  dynamic_state.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
  dynamic_state.dynamicStateCount = static_cast<uint32_t>(dynamic.size());
  dynamic_state.pDynamicStates = dynamic.data();

  VkPipelineRenderingCreateInfo rendering{};

  rendering.sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO;
  rendering.colorAttachmentCount = static_cast<uint32_t>(desc.color_formats.size());
  rendering.pColorAttachmentFormats = desc.color_formats.data();
  rendering.depthAttachmentFormat = desc.depth_format;

  VkGraphicsPipelineCreateInfo info{};

  info.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
  if (desc.render_pass) {
    info.renderPass = desc.render_pass;
    info.subpass = desc.subpass;
  } else {
    info.pNext = &rendering;
  }
  info.stageCount = has_fragment ? 2 : 1;
  info.pStages = stage_info;
  info.pVertexInputState = &vertex_input;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &color_blend;
  info.pDynamicState = &dynamic_state;
  info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  vk_check(vkCreateGraphicsPipelines(device.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
           "vkCreateGraphicsPipelines");
  return named_pipeline(device, pipeline, std::move(layout), desc.debug_name, VK_PIPELINE_BIND_POINT_GRAPHICS, stages);
}

}  // namespace tressvk::engine
