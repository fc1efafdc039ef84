// TvkRenderer: creation, destruction and pipeline building (on first use). The recording calls are in
// render_draw.cpp.
#include "render.hpp"

#include "tressvk_render_spirv.h"

#include <algorithm>
#include <new>

namespace tressvk::render {

namespace {

TvkResult make_set_layout(Context& ctx, bool shadowed, VkDescriptorSetLayout& out) {
  std::array<VkDescriptorSetLayoutBinding, 6> b{};
  for (uint32_t i = 0; i < 6; ++i) {
    b[i].binding = i;
    b[i].descriptorCount = 1;
    b[i].descriptorType = i == 0 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    b[i].stageFlags = i == 0 ? VkShaderStageFlags{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT}
                           : VkShaderStageFlags{VK_SHADER_STAGE_VERTEX_BIT};
  }
  b[5].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  b[5].stageFlags = VK_SHADER_STAGE_FRAGMENT_BIT;
  VkDescriptorSetLayoutCreateInfo ci{};
  ci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  ci.bindingCount = shadowed ? 6u : 5u;
  ci.pBindings = b.data();
  return ctx.check(ctx.vk.vkCreateDescriptorSetLayout(ctx.info.device, &ci, ctx.info.allocator, &out),
                   "vkCreateDescriptorSetLayout (hair)");
}

TvkResult make_pipeline_layout(Context& ctx, VkDescriptorSetLayout set, VkPipelineLayout& out) {
  VkPipelineLayoutCreateInfo ci{};
  ci.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  ci.setLayoutCount = 1;
  ci.pSetLayouts = &set;
  return ctx.check(ctx.vk.vkCreatePipelineLayout(ctx.info.device, &ci, ctx.info.allocator, &out),
                   "vkCreatePipelineLayout (hair)");
}

template <size_t N>
TvkResult make_module(Context& ctx, const uint32_t (&code)[N], VkShaderModule& out) {
  VkShaderModuleCreateInfo ci{};
  ci.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  ci.codeSize = sizeof(code);
  ci.pCode = code;
  return ctx.check(ctx.vk.vkCreateShaderModule(ctx.info.device, &ci, ctx.info.allocator, &out),
                   "vkCreateShaderModule (hair)");
}

}  // namespace

TvkResult create_pipeline(TvkRenderer_T& r, PipelineKind kind) {
  Context& ctx = *r.ctx;
  const bool shadow = kind == PipelineKind::shadow;
  const bool shadowed = kind == PipelineKind::core_shadowed || kind == PipelineKind::fringe_shadowed;
  const bool fringe = kind == PipelineKind::fringe || kind == PipelineKind::fringe_shadowed;
  const TvkRenderTarget& target = shadow ? r.info.shadow : r.info.shading;

  VkShaderModule vs = VK_NULL_HANDLE, fs = VK_NULL_HANDLE;
  TvkResult res = shadow ? make_module(ctx, k_spv_hair_shadow_vert, vs) : make_module(ctx, k_spv_hair_vert, vs);
  if (res == TVK_SUCCESS && !shadow)
    res = shadowed ? make_module(ctx, k_spv_hair_shadowed_frag, fs) : make_module(ctx, k_spv_hair_frag, fs);
  if (res != TVK_SUCCESS) {
    if (vs) ctx.vk.vkDestroyShaderModule(ctx.info.device, vs, ctx.info.allocator);
    return res;
  }

  const uint32_t pass = fringe ? 1u : 0u;
  const VkSpecializationMapEntry entry{0, 0, sizeof(uint32_t)};
  VkSpecializationInfo spec{};
  spec.mapEntryCount = 1;
  spec.pMapEntries = &entry;
  spec.dataSize = sizeof(pass);
  spec.pData = &pass;
  std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
  stages[0].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vs;
  stages[0].pName = "main";
  stages[1] = stages[0];
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fs;
  stages[1].pSpecializationInfo = &spec;

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
  rs.cullMode = VK_CULL_MODE_NONE;  // the quads' winding depends on the strand's screen direction
  rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  rs.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{};
  ms.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
  ms.rasterizationSamples = target.samples ? target.samples : VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo ds{};
  ds.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
  ds.depthTestEnable = VK_TRUE;
  ds.depthWriteEnable = fringe ? VK_FALSE : VK_TRUE;
  ds.depthCompareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
  VkPipelineColorBlendAttachmentState blend{};
  blend.colorWriteMask =
      VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  if (fringe) {  // premultiplied "over"
    blend.blendEnable = VK_TRUE;
    blend.srcColorBlendFactor = VK_BLEND_FACTOR_ONE;
    blend.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    blend.colorBlendOp = VK_BLEND_OP_ADD;
    blend.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    blend.alphaBlendOp = VK_BLEND_OP_ADD;
  }
  VkPipelineColorBlendStateCreateInfo cb{};
  cb.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
  cb.attachmentCount = shadow ? 0u : 1u;
  cb.pAttachments = &blend;
  const std::array<VkDynamicState, 2> dyn{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dy{};
  dy.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
  dy.dynamicStateCount = static_cast<uint32_t>(dyn.size());
  dy.pDynamicStates = dyn.data();

  VkPipelineRenderingCreateInfo ri{};
  ri.sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO;
  ri.colorAttachmentCount = shadow ? 0u : 1u;
  ri.pColorAttachmentFormats = &target.color_format;
  ri.depthAttachmentFormat = target.depth_format;

  VkGraphicsPipelineCreateInfo ci{};
  ci.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
  ci.pNext = target.render_pass ? nullptr : &ri;
  ci.stageCount = shadow ? 1u : 2u;
  ci.pStages = stages.data();
  ci.pVertexInputState = &vi;
  ci.pInputAssemblyState = &ia;
  ci.pViewportState = &vp;
  ci.pRasterizationState = &rs;
  ci.pMultisampleState = &ms;
  ci.pDepthStencilState = &ds;
  ci.pColorBlendState = &cb;
  ci.pDynamicState = &dy;
  ci.layout = shadowed ? r.shadowed_pipeline_layout : r.pipeline_layout;
  ci.renderPass = target.render_pass;
  ci.subpass = target.subpass;
  VkPipeline pipeline = VK_NULL_HANDLE;
  res = ctx.check(ctx.vk.vkCreateGraphicsPipelines(ctx.info.device, ctx.info.pipeline_cache, 1, &ci,
                                                   ctx.info.allocator, &pipeline),
                  "vkCreateGraphicsPipelines (hair)");
  ctx.vk.vkDestroyShaderModule(ctx.info.device, vs, ctx.info.allocator);
  if (fs) ctx.vk.vkDestroyShaderModule(ctx.info.device, fs, ctx.info.allocator);
  if (res == TVK_SUCCESS) r.pipelines[static_cast<size_t>(kind)] = pipeline;
  return res;
}

}  // namespace tressvk::render

void TvkRenderer_T::destroy() {
  tressvk::Context& c = *ctx;
  const VkDevice dev = c.info.device;
  for (VkPipeline& p : pipelines)
    if (p) c.vk.vkDestroyPipeline(dev, p, c.info.allocator);
  for (VkDescriptorPool p : pools)
    if (p) c.vk.vkDestroyDescriptorPool(dev, p, c.info.allocator);
  for (VkDescriptorPool p : compute_pools)
    if (p) c.vk.vkDestroyDescriptorPool(dev, p, c.info.allocator);
  tressvk::render::compute::destroy(*this);
  if (pipeline_layout) c.vk.vkDestroyPipelineLayout(dev, pipeline_layout, c.info.allocator);
  if (shadowed_pipeline_layout) c.vk.vkDestroyPipelineLayout(dev, shadowed_pipeline_layout, c.info.allocator);
  if (set_layout) c.vk.vkDestroyDescriptorSetLayout(dev, set_layout, c.info.allocator);
  if (shadowed_set_layout) c.vk.vkDestroyDescriptorSetLayout(dev, shadowed_set_layout, c.info.allocator);
  tressvk::destroy_buffer(c, ring);
}

extern "C" {

TvkResult tressvk_create_renderer(TvkContext context, const TvkRendererCreateInfo* info, TvkRenderer* out_renderer) {
  using namespace tressvk;
  if (!context) return TVK_ERROR_INVALID_ARGUMENT;
  Context& ctx = *context;
  if (!out_renderer) return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_create_renderer: out_renderer is NULL");
  *out_renderer = nullptr;
  if (const TvkResult lost = ctx.require_device("tressvk_create_renderer"); lost != TVK_SUCCESS) return lost;
  if (!info || info->struct_size != sizeof(TvkRendererCreateInfo))
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_create_renderer: info is NULL or has a wrong struct_size");
  if (info->shading.depth_format == VK_FORMAT_UNDEFINED || info->shading.color_format == VK_FORMAT_UNDEFINED)
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT,
                    "tressvk_create_renderer: shading.color_format and shading.depth_format are required");
  TvkRenderer_T* r = new (std::nothrow) TvkRenderer_T{};
  if (!r) return ctx.fail(TVK_ERROR_OUT_OF_MEMORY, "tressvk_create_renderer: out of host memory");
  r->ctx = &ctx;
  r->info = *info;
  r->info.next = nullptr;
  r->max_draws = info->max_draws_per_frame ? info->max_draws_per_frame : 64u;
  const VkDeviceSize align = std::max<VkDeviceSize>(16, ctx.device_properties.limits.minUniformBufferOffsetAlignment);
  r->block_stride = (sizeof(render::DrawConstants) + align - 1) / align * align;

  TvkResult res = render::make_set_layout(ctx, false, r->set_layout);
  if (res == TVK_SUCCESS) res = render::make_set_layout(ctx, true, r->shadowed_set_layout);
  if (res == TVK_SUCCESS) res = render::make_pipeline_layout(ctx, r->set_layout, r->pipeline_layout);
  if (res == TVK_SUCCESS)
    res = render::make_pipeline_layout(ctx, r->shadowed_set_layout, r->shadowed_pipeline_layout);
  if (res == TVK_SUCCESS)
    res = create_buffer(ctx, r->block_stride * r->max_draws * ctx.frames_in_flight, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                        Memory::host_upload, "hair draw constants", r->ring);
  for (uint32_t i = 0; res == TVK_SUCCESS && i < ctx.frames_in_flight; ++i) {
    const std::array<VkDescriptorPoolSize, 3> sizes{
        VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, r->max_draws},
        VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 4 * r->max_draws},
        VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, r->max_draws}};
    VkDescriptorPoolCreateInfo pci{};
    pci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pci.maxSets = r->max_draws;
    pci.poolSizeCount = static_cast<uint32_t>(sizes.size());
    pci.pPoolSizes = sizes.data();
    VkDescriptorPool pool = VK_NULL_HANDLE;
    res = ctx.check(ctx.vk.vkCreateDescriptorPool(ctx.info.device, &pci, ctx.info.allocator, &pool),
                    "vkCreateDescriptorPool (hair)");
    if (res == TVK_SUCCESS) r->pools.push_back(pool);
  }
  if (res != TVK_SUCCESS) {
    r->destroy();
    delete r;
    return res;
  }
  *out_renderer = r;
  return TVK_SUCCESS;
}

void tressvk_destroy_renderer(TvkRenderer renderer) {
  if (!renderer) return;
  renderer->destroy();
  delete renderer;
}

uint32_t tressvk_get_last_drawn_strands(TvkRenderer renderer) { return renderer ? renderer->last_drawn_strands : 0u; }

}  // extern "C"
