#include "core/pipelines.hpp"

#include <array>
#include <vector>

namespace tressvk {

namespace {

struct Spec {
  std::vector<VkSpecializationMapEntry> entries;
  VkSpecializationInfo info{};
  explicit Spec(std::span<const uint32_t> values) {
    for (uint32_t i = 0; i < values.size(); ++i)
      entries.push_back({i, static_cast<uint32_t>(i * sizeof(uint32_t)), sizeof(uint32_t)});
    info.mapEntryCount = static_cast<uint32_t>(entries.size());
    info.pMapEntries = entries.data();
    info.dataSize = values.size_bytes();
    info.pData = values.data();
  }
  const VkSpecializationInfo* get() const { return entries.empty() ? nullptr : &info; }
};

}  // namespace

TvkResult create_shader_module(Context& ctx, ShaderCode code, const char* what, VkShaderModule& out) {
  VkShaderModuleCreateInfo ci{};
  ci.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  ci.codeSize = code.bytes;
  ci.pCode = code.code;
  return ctx.check(ctx.vk.vkCreateShaderModule(ctx.info.device, &ci, ctx.info.allocator, &out), what);
}

TvkResult create_compute_pipeline(Context& ctx, VkPipelineLayout layout, ShaderCode code,
                                  std::span<const uint32_t> spec, const char* what, VkPipeline& out) {
  VkShaderModule module = VK_NULL_HANDLE;
  if (TvkResult res = create_shader_module(ctx, code, "vkCreateShaderModule (hair compute)", module);
      res != TVK_SUCCESS)
    return res;
  const Spec si(spec);
  VkComputePipelineCreateInfo ci{};
  ci.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  ci.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  ci.stage.module = module;
  ci.stage.pName = "main";
  ci.stage.pSpecializationInfo = si.get();
  ci.layout = layout;
  const TvkResult res = ctx.check(
      ctx.vk.vkCreateComputePipelines(ctx.info.device, ctx.info.pipeline_cache, 1, &ci, ctx.info.allocator, &out),
      what);
  ctx.vk.vkDestroyShaderModule(ctx.info.device, module, ctx.info.allocator);
  return res;
}

TvkResult create_graphics_pipeline(Context& ctx, const GraphicsPipelineDesc& desc, const char* module_what,
                                   const char* what, VkPipeline& out) {
  const TvkRenderTarget& target = *desc.target;
  const bool color = desc.fragment.code != nullptr;
  VkShaderModule vs = VK_NULL_HANDLE, fs = VK_NULL_HANDLE;
  TvkResult res = create_shader_module(ctx, desc.vertex, module_what, vs);
  if (res == TVK_SUCCESS && color) res = create_shader_module(ctx, desc.fragment, module_what, fs);
  if (res != TVK_SUCCESS) {
    if (vs) ctx.vk.vkDestroyShaderModule(ctx.info.device, vs, ctx.info.allocator);
    return res;
  }
  const Spec spec(desc.fragment_spec);
  std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
  stages[0].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vs;
  stages[0].pName = "main";
  stages[1] = stages[0];
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fs;
  stages[1].pSpecializationInfo = spec.get();

  VkPipelineVertexInputStateCreateInfo vi{};
  vi.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
  VkPipelineInputAssemblyStateCreateInfo ia{};
  ia.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
  ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo vp{};
  vp.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
  vp.viewportCount = 1;
  vp.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo rs{};
  rs.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  rs.cullMode = VK_CULL_MODE_NONE;  // the hair quads' winding depends on the strand's screen direction
  rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  rs.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{};
  ms.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
  ms.rasterizationSamples = target.samples ? target.samples : VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo ds{};
  ds.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
  if (desc.depth_test) {
    ds.depthTestEnable = VK_TRUE;
    ds.depthWriteEnable = desc.depth_write ? VK_TRUE : VK_FALSE;
    ds.depthCompareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
  }
  // out = src + dst * (1 - src.alpha) for colour and alpha (premultiplied "over"), or the source alone.
  const VkPipelineColorBlendAttachmentState blend{
      desc.premultiplied_over ? VK_TRUE : VK_FALSE,
      VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA, VK_BLEND_OP_ADD,
      VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA, VK_BLEND_OP_ADD,
      VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT};
  VkPipelineColorBlendStateCreateInfo cb{};
  cb.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
  cb.attachmentCount = color ? 1u : 0u;
  cb.pAttachments = &blend;
  const std::array<VkDynamicState, 2> dyn{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dy{};
  dy.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
  dy.dynamicStateCount = static_cast<uint32_t>(dyn.size());
  dy.pDynamicStates = dyn.data();

  VkPipelineRenderingCreateInfo ri{};
  ri.sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO;
  ri.colorAttachmentCount = color ? 1u : 0u;
  ri.pColorAttachmentFormats = &target.color_format;
  ri.depthAttachmentFormat = target.depth_format;

  VkGraphicsPipelineCreateInfo ci{};
  ci.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
  ci.pNext = target.render_pass ? nullptr : &ri;
  ci.stageCount = color ? 2u : 1u;
  ci.pStages = stages.data();
  ci.pVertexInputState = &vi;
  ci.pInputAssemblyState = &ia;
  ci.pViewportState = &vp;
  ci.pRasterizationState = &rs;
  ci.pMultisampleState = &ms;
  ci.pDepthStencilState = &ds;
  ci.pColorBlendState = &cb;
  ci.pDynamicState = &dy;
  ci.layout = desc.layout;
  ci.renderPass = target.render_pass;
  ci.subpass = target.subpass;
  res = ctx.check(
      ctx.vk.vkCreateGraphicsPipelines(ctx.info.device, ctx.info.pipeline_cache, 1, &ci, ctx.info.allocator, &out),
      what);
  ctx.vk.vkDestroyShaderModule(ctx.info.device, vs, ctx.info.allocator);
  if (fs) ctx.vk.vkDestroyShaderModule(ctx.info.device, fs, ctx.info.allocator);
  return res;
}

}  // namespace tressvk
