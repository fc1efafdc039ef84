// TvkRenderer: creation, destruction and pipeline building (on first use). The recording calls are in
// draw.cpp.
#include "render/render.hpp"
#include "render/compute/state.hpp"
#include "core/objects.hpp"
#include "core/pipelines.hpp"

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

}  // namespace

TvkResult create_pipeline(TvkRenderer_T& r, PipelineKind kind) {
  const bool shadow = kind == PipelineKind::shadow;
  const bool shadowed = kind == PipelineKind::core_shadowed || kind == PipelineKind::fringe_shadowed;
  const bool fringe = kind == PipelineKind::fringe || kind == PipelineKind::fringe_shadowed;
  const uint32_t pass = fringe ? 1u : 0u;  // the fragment shader's specialisation: core or fringe
  GraphicsPipelineDesc desc;
  desc.vertex = shadow ? spirv(k_spv_hair_shadow_vert) : spirv(k_spv_hair_vert);
  if (!shadow) desc.fragment = shadowed ? spirv(k_spv_hair_shadowed_frag) : spirv(k_spv_hair_frag);
  desc.fragment_spec = std::span<const uint32_t>(&pass, 1);
  desc.target = shadow ? &r.info.shadow : &r.info.shading;
  desc.layout = shadowed ? r.shadowed_pipeline_layout : r.pipeline_layout;
  desc.depth_test = true;
  desc.depth_write = !fringe;
  desc.premultiplied_over = fringe;
  VkPipeline pipeline = VK_NULL_HANDLE;
  const TvkResult res = create_graphics_pipeline(*r.ctx, desc, "vkCreateShaderModule (hair)",
                                                 "vkCreateGraphicsPipelines (hair)", pipeline);
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

TvkResult tressvk_prewarm_renderer(TvkRenderer renderer) {
  if (!renderer)
    return tressvk::fail_without_context(TVK_ERROR_INVALID_ARGUMENT, "tressvk_prewarm_renderer: renderer is NULL");
  TvkRenderer_T& r = *renderer;
  return tressvk::guarded(*r.ctx, "tressvk_prewarm_renderer", [&]() -> TvkResult {
    using tressvk::render::PipelineKind;
    const bool shadow = r.info.shadow.depth_format != VK_FORMAT_UNDEFINED;
    for (PipelineKind kind : {PipelineKind::shadow, PipelineKind::core, PipelineKind::fringe,
                              PipelineKind::core_shadowed, PipelineKind::fringe_shadowed}) {
      if ((kind == PipelineKind::shadow && !shadow) || r.pipelines[static_cast<size_t>(kind)]) continue;
      if (TvkResult res = tressvk::render::create_pipeline(r, kind); res != TVK_SUCCESS) return res;
    }
    if (TvkResult res = tressvk::render::compute::ensure_pipelines(r); res != TVK_SUCCESS) return res;
    if (TvkResult res = tressvk::render::compute::ensure_composite_pipeline(r); res != TVK_SUCCESS) return res;
    if (shadow)
      if (TvkResult res = tressvk::render::compute::ensure_shadow_pipeline(r); res != TVK_SUCCESS) return res;
    return TVK_SUCCESS;
  });
}

uint32_t tressvk_get_last_drawn_strands(TvkRenderer renderer) { return renderer ? renderer->last_drawn_strands : 0u; }

TvkResult tressvk_get_draw_strands(TvkRenderer renderer, const TvkDrawInfo* info, uint32_t* out_strands) {
  if (!renderer || !out_strands)
    return tressvk::fail_without_context(TVK_ERROR_INVALID_ARGUMENT,
                                         "tressvk_get_draw_strands: renderer or out_strands is NULL");
  tressvk::Context& ctx = *renderer->ctx;
  if (!info || info->struct_size != sizeof(TvkDrawInfo) || !info->instance || !info->view)
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_get_draw_strands: info (struct_size), instance or view missing");
  if (info->instance->ctx != &ctx)
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_get_draw_strands: the instance belongs to another context");
  *out_strands = tressvk::render::lod_strands(info, info->lod_view ? *info->lod_view : *info->view);
  return TVK_SUCCESS;
}

}  // extern "C"
