// The compute rasterizer's Vulkan objects: descriptor set and pipeline layouts, its compute pipelines, the
// nearest sampler, per-slot descriptor pools, and buffers grown (never shrunk, never reallocated per frame) to
// the largest view and groom seen.
#include "state.hpp"

#include "core/pipelines.hpp"

#include "tressvk_render_spirv.h"

#include <algorithm>
#include <array>
#include <initializer_list>
#include <new>

namespace tressvk::render::compute {

namespace {

template <size_t N>
TvkResult make_compute(Context& ctx, VkPipelineLayout layout, const uint32_t (&code)[N],
                       std::initializer_list<uint32_t> specs, VkPipeline& out) {
  // Specialization constants 0, 1, ... in order.
  return create_compute_pipeline(ctx, layout, spirv(code), std::span<const uint32_t>(specs.begin(), specs.size()),
                                 "vkCreateComputePipelines (hair compute)", out);
}

VkDescriptorType binding_type(uint32_t b) {
  if (b == kConstants) return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  if (b == kShadowMap || b == kHostDepth) return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

}  // namespace

TvkResult grow(Context& ctx, GpuBuffer& buffer, VkDeviceSize size, VkBufferUsageFlags usage, Memory memory,
               const char* name) {
  if (buffer && buffer.size >= size) return TVK_SUCCESS;
  if (buffer) destroy_buffer_deferred(ctx, buffer);
  buffer = GpuBuffer{};
  return create_buffer(ctx, size, usage, memory, name, buffer);
}

TvkResult ensure_shadow_pipeline(TvkRenderer_T& r) {
  Context& ctx = *r.ctx;
  State& s = *r.compute;
  if (s.shadow) return TVK_SUCCESS;
  if (!s.shadow_set_layout) {
    std::array<VkDescriptorSetLayoutBinding, 6> b{};
    for (uint32_t i = 0; i < 6; ++i) {
      b[i].binding = i;
      b[i].descriptorCount = 1;
      b[i].descriptorType = i == 0 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
      b[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    VkDescriptorSetLayoutCreateInfo ci{};
    ci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    ci.bindingCount = 6;
    ci.pBindings = b.data();
    if (TvkResult res = ctx.check(ctx.vk.vkCreateDescriptorSetLayout(ctx.info.device, &ci, ctx.info.allocator,
                                                                      &s.shadow_set_layout),
                                  "vkCreateDescriptorSetLayout (hair shadow compute)");
        res != TVK_SUCCESS)
      return res;
    const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(Push)};
    VkPipelineLayoutCreateInfo pci{};
    pci.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    pci.setLayoutCount = 1;
    pci.pSetLayouts = &s.shadow_set_layout;
    pci.pushConstantRangeCount = 1;
    pci.pPushConstantRanges = &range;
    if (TvkResult res = ctx.check(ctx.vk.vkCreatePipelineLayout(ctx.info.device, &pci, ctx.info.allocator,
                                                                 &s.shadow_layout),
                                  "vkCreatePipelineLayout (hair shadow compute)");
        res != TVK_SUCCESS)
      return res;
  }
  return make_compute(ctx, s.shadow_layout, k_spv_shadow_depth_comp, {0}, s.shadow);
}

TvkResult ensure_pipelines(TvkRenderer_T& r) {
  Context& ctx = *r.ctx;
  if (!r.compute) {
    r.compute = new (std::nothrow) State{};
    if (!r.compute) return ctx.fail(TVK_ERROR_OUT_OF_MEMORY, "hair compute rasterizer: out of host memory");
  }
  State& s = *r.compute;
  if (std::all_of(s.pipelines.begin(), s.pipelines.end(), [](VkPipeline p) { return p != VK_NULL_HANDLE; }))
    return TVK_SUCCESS;
  if (!s.set_layout) {
    std::array<VkDescriptorSetLayoutBinding, kBindingCount> b{};
    for (uint32_t i = 0; i < kBindingCount; ++i) {
      b[i].binding = i;
      b[i].descriptorCount = 1;
      b[i].descriptorType = binding_type(i);
      b[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    VkDescriptorSetLayoutCreateInfo ci{};
    ci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    ci.bindingCount = kBindingCount;
    ci.pBindings = b.data();
    if (TvkResult res = ctx.check(ctx.vk.vkCreateDescriptorSetLayout(ctx.info.device, &ci, ctx.info.allocator,
                                                                      &s.set_layout),
                                  "vkCreateDescriptorSetLayout (hair compute)");
        res != TVK_SUCCESS)
      return res;
  }
  if (!s.layout) {
    const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(Push)};
    VkPipelineLayoutCreateInfo ci{};
    ci.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    ci.setLayoutCount = 1;
    ci.pSetLayouts = &s.set_layout;
    ci.pushConstantRangeCount = 1;
    ci.pPushConstantRanges = &range;
    if (TvkResult res = ctx.check(ctx.vk.vkCreatePipelineLayout(ctx.info.device, &ci, ctx.info.allocator, &s.layout),
                                  "vkCreatePipelineLayout (hair compute)");
        res != TVK_SUCCESS)
      return res;
  }
  if (!s.sampler) {
    VkSamplerCreateInfo ci{};
    ci.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
    ci.magFilter = ci.minFilter = VK_FILTER_NEAREST;
    ci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    ci.addressModeU = ci.addressModeV = ci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    ci.maxLod = 0.0f;
    if (TvkResult res = ctx.check(ctx.vk.vkCreateSampler(ctx.info.device, &ci, ctx.info.allocator, &s.sampler),
                                  "vkCreateSampler (hair compute)");
        res != TVK_SUCCESS)
      return res;
  }
  if (r.compute_pools.empty()) {
    for (uint32_t i = 0; i < ctx.frames_in_flight; ++i) {
      const std::array<VkDescriptorPoolSize, 3> sizes{
          VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 2 * r.max_draws},
          VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 19 * r.max_draws},
          VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2 * r.max_draws}};
      VkDescriptorPoolCreateInfo pci{};
      pci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
      pci.maxSets = 3 * r.max_draws;  // a shadow, a raster and a composite set per draw
      pci.poolSizeCount = static_cast<uint32_t>(sizes.size());
      pci.pPoolSizes = sizes.data();
      VkDescriptorPool pool = VK_NULL_HANDLE;
      if (TvkResult res = ctx.check(ctx.vk.vkCreateDescriptorPool(ctx.info.device, &pci, ctx.info.allocator, &pool),
                                    "vkCreateDescriptorPool (hair compute)");
          res != TVK_SUCCESS)
        return res;
      r.compute_pools.push_back(pool);
    }
  }
  auto& p = s.pipelines;
  TvkResult res = TVK_SUCCESS;
  if (res == TVK_SUCCESS && !p[0]) res = make_compute(ctx, s.layout, k_spv_project_comp, {0}, p[0]);
  if (res == TVK_SUCCESS && !p[12]) res = make_compute(ctx, s.layout, k_spv_vertex_comp, {0}, p[12]);
  if (res == TVK_SUCCESS && !p[1]) res = make_compute(ctx, s.layout, k_spv_tile_depth_comp, {0}, p[1]);
  if (res == TVK_SUCCESS && !p[2]) res = make_compute(ctx, s.layout, k_spv_bin_comp, {0}, p[2]);
  if (res == TVK_SUCCESS && !p[3]) res = make_compute(ctx, s.layout, k_spv_scan_comp, {0}, p[3]);
  if (res == TVK_SUCCESS && !p[4]) res = make_compute(ctx, s.layout, k_spv_bin_comp, {1}, p[4]);
  if (res == TVK_SUCCESS && !p[11]) res = make_compute(ctx, s.layout, k_spv_scan_comp, {1}, p[11]);
  // fine.comp's specialization constants: shared-memory entries, slice, reorder window, per fragment, split pass,
  // settle fragments (state.hpp).
  if (res == TVK_SUCCESS && !p[5])
    res = make_compute(ctx, s.layout, k_spv_fine_comp,
                       {kSliceCapacity, kSliceEntries, kReorderWindow, 0, 0, kSettleFragments}, p[5]);
  if (res == TVK_SUCCESS && !p[6]) res = make_compute(ctx, s.layout, k_spv_dom_comp, {0}, p[6]);
  if (res == TVK_SUCCESS && !p[7]) res = make_compute(ctx, s.layout, k_spv_dom_comp, {1}, p[7]);
  if (res == TVK_SUCCESS && !p[13]) res = make_compute(ctx, s.layout, k_spv_dom_comp, {2}, p[13]);
  if (res == TVK_SUCCESS && !p[8])
    res = make_compute(ctx, s.layout, k_spv_fine_comp,
                       {kSliceCapacity, kSliceEntries, kReorderWindow, 1, 0, kSettleFragments}, p[8]);
  if (res == TVK_SUCCESS && !p[9])
    res = make_compute(ctx, s.layout, k_spv_fine_comp,
                       {kSplitCapacity, kSliceEntries, kReorderWindow, 0, 1, kSettleFragments}, p[9]);
  if (res == TVK_SUCCESS && !p[10])
    res = make_compute(ctx, s.layout, k_spv_fine_comp,
                       {kSplitCapacity, kSliceEntries, kReorderWindow, 1, 1, kSettleFragments}, p[10]);
  return res;
}

TvkResult ensure_composite_pipeline(TvkRenderer_T& r) {
  Context& ctx = *r.ctx;
  State& s = *r.compute;
  if (s.composite) return TVK_SUCCESS;
  if (!s.composite_set_layout) {
    VkDescriptorSetLayoutBinding b{};
    b.binding = 0;
    b.descriptorCount = 1;
    b.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    b.stageFlags = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;  // the vertex shader reads the bounds
    VkDescriptorSetLayoutCreateInfo ci{};
    ci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    ci.bindingCount = 1;
    ci.pBindings = &b;
    if (TvkResult res = ctx.check(ctx.vk.vkCreateDescriptorSetLayout(ctx.info.device, &ci, ctx.info.allocator,
                                                                      &s.composite_set_layout),
                                  "vkCreateDescriptorSetLayout (hair composite)");
        res != TVK_SUCCESS)
      return res;
    const VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, 16};
    VkPipelineLayoutCreateInfo pci{};
    pci.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    pci.setLayoutCount = 1;
    pci.pSetLayouts = &s.composite_set_layout;
    pci.pushConstantRangeCount = 1;
    pci.pPushConstantRanges = &range;
    if (TvkResult res = ctx.check(ctx.vk.vkCreatePipelineLayout(ctx.info.device, &pci, ctx.info.allocator,
                                                                 &s.composite_layout),
                                  "vkCreatePipelineLayout (hair composite)");
        res != TVK_SUCCESS)
      return res;
  }
  GraphicsPipelineDesc desc;
  desc.vertex = spirv(k_spv_composite_vert);
  desc.fragment = spirv(k_spv_composite_frag);
  desc.target = &r.info.shading;
  desc.layout = s.composite_layout;
  desc.premultiplied_over = true;
  return create_graphics_pipeline(ctx, desc, "vkCreateShaderModule (hair compute)",
                                  "vkCreateGraphicsPipelines (hair composite)", s.composite);
}

TvkResult ensure_buffers(TvkRenderer_T& r, uint32_t width, uint32_t height, uint64_t vertices, uint64_t segments,
                         bool capture, bool per_fragment) {
  Context& ctx = *r.ctx;
  State& s = *r.compute;
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  const uint64_t max_range = ctx.device_properties.limits.maxStorageBufferRange;
  const uint64_t pixels = uint64_t{width} * height;
  const uint64_t tiles = uint64_t{(width + kTile - 1) / kTile} * ((height + kTile - 1) / kTile);
  const uint64_t capacity = std::min<uint64_t>(std::max<uint64_t>(12 * segments, 1u << 20), max_range / 8);
  // 6 words per tile, 2 per block of 1024, then the fine pass's indirect dispatch and list size (8 words), a count
  // and a cursor per weight bucket (2 x 128 words) and the list of tiles (raster_layout.glsl).
  const uint64_t blocks = (tiles + 1023) / 1024;
  const uint64_t tile_bytes = 24 * tiles + 8 * blocks + 32 + 8 * 128 + 4 * tiles;
  if (32 * vertices > max_range || 8 * pixels > max_range || tile_bytes > max_range)
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT,
                    "tressvk_cmd_raster_hair: %llu strand vertices or a %ux%u view exceed the device's storage "
                    "buffer range (%llu bytes)",
                    static_cast<unsigned long long>(vertices), width, height,
                    static_cast<unsigned long long>(max_range));
  TvkResult res = grow(ctx, s.verts, std::max<uint64_t>((per_fragment ? 64 : 32) * vertices, 64), storage,
                       Memory::device, "hair compute vertices");
  if (res == TVK_SUCCESS) res = grow(ctx, s.tiles, tile_bytes, storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, Memory::device,
                                      "hair compute tiles");
  if (res == TVK_SUCCESS && s.entry_capacity < capacity) {
    res = grow(ctx, s.entries, 8 * capacity, storage, Memory::device, "hair compute tile entries");
    if (res == TVK_SUCCESS) s.entry_capacity = static_cast<uint32_t>(capacity);
  }
  // Split work items: enough for the entry capacity in shares of kSplit plus 1,024 (a tile's last share is partial).
  const uint64_t slots = std::min<uint64_t>(kSplitSlots, capacity / kSplit + 1024);
  if (res == TVK_SUCCESS)
    res = grow(ctx, s.split_items, 8 * (4 + slots), storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, Memory::device,
               "hair compute split items");
  if (res == TVK_SUCCESS && s.split_slots < slots) {
    res = grow(ctx, s.partials, 8 * 64 * slots, storage, Memory::device, "hair compute partial layers");
    if (res == TVK_SUCCESS) s.split_slots = static_cast<uint32_t>(slots);
  }
  if (res == TVK_SUCCESS)
    res = grow(ctx, s.counters, 4 * kCounterCount, storage, Memory::device, "hair compute counters");
  // The layer, then the composite's VkDrawIndirectCommand and its list of tiles with hair (fine.comp).
  if (res == TVK_SUCCESS)
    res = grow(ctx, s.image, 8 * pixels + 16 + 8 * tiles, storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
               Memory::device, "hair compute layer");
  if (res == TVK_SUCCESS && !s.dom) {
    res = grow(ctx, s.dom, 4ull * kDomSize * kDomSize * (1 + kDomLayers), storage, Memory::device,
               "hair deep opacity map");
    s.dom_dirty = true;
  }
  if (res == TVK_SUCCESS)
    res = grow(ctx, s.stats_readback, 4 * kCounterCount + 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, Memory::host_readback,
               "hair compute statistics");
  // The capture depth binding always needs a buffer; a pixel-sized one only when capturing.
  if (res == TVK_SUCCESS)
    res = grow(ctx, s.capture_depth, capture ? 4 * pixels : 16, storage, Memory::device, "hair compute capture");
  if (res == TVK_SUCCESS && capture) {
    res = grow(ctx, s.capture_verts, 32 * std::max<uint64_t>(vertices, 2), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
               Memory::host_readback, "hair capture vertices");
    if (res == TVK_SUCCESS)
      res = grow(ctx, s.capture_host_depth, 4 * pixels, VK_BUFFER_USAGE_TRANSFER_DST_BIT, Memory::host_readback,
                 "hair capture depth");
    if (res == TVK_SUCCESS)
      res = grow(ctx, s.capture_image, 8 * pixels, VK_BUFFER_USAGE_TRANSFER_DST_BIT, Memory::host_readback,
                 "hair capture layer");
  }
  return res;
}

uint64_t memory_bytes(const State& s) {
  return s.verts.size + s.tiles.size + s.entries.size + s.counters.size + s.image.size + s.capture_depth.size +
         s.dom.size + s.shadow_depth.size + s.split_items.size + s.partials.size;
}

void destroy(TvkRenderer_T& r) {
  if (!r.compute) return;
  Context& c = *r.ctx;
  State& s = *r.compute;
  const VkDevice dev = c.info.device;
  for (VkPipeline p : s.pipelines)
    if (p) c.vk.vkDestroyPipeline(dev, p, c.info.allocator);
  if (s.composite) c.vk.vkDestroyPipeline(dev, s.composite, c.info.allocator);
  if (s.shadow) c.vk.vkDestroyPipeline(dev, s.shadow, c.info.allocator);
  if (s.shadow_layout) c.vk.vkDestroyPipelineLayout(dev, s.shadow_layout, c.info.allocator);
  if (s.shadow_set_layout) c.vk.vkDestroyDescriptorSetLayout(dev, s.shadow_set_layout, c.info.allocator);
  if (s.layout) c.vk.vkDestroyPipelineLayout(dev, s.layout, c.info.allocator);
  if (s.composite_layout) c.vk.vkDestroyPipelineLayout(dev, s.composite_layout, c.info.allocator);
  if (s.set_layout) c.vk.vkDestroyDescriptorSetLayout(dev, s.set_layout, c.info.allocator);
  if (s.composite_set_layout) c.vk.vkDestroyDescriptorSetLayout(dev, s.composite_set_layout, c.info.allocator);
  if (s.sampler) c.vk.vkDestroySampler(dev, s.sampler, c.info.allocator);
  for (GpuBuffer* b : {&s.split_items, &s.partials, &s.shadow_depth, &s.dom, &s.verts, &s.tiles, &s.entries, &s.counters, &s.image, &s.capture_depth, &s.stats_readback,
                       &s.capture_verts, &s.capture_host_depth, &s.capture_image})
    destroy_buffer(c, *b);
  delete r.compute;
  r.compute = nullptr;
}

// One global memory barrier (the compute passes order their own buffers with it).
void memory_barrier(Context& ctx, VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                    VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access) {
  VkMemoryBarrier2 b{};
  b.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2;
  b.srcStageMask = src_stage;
  b.srcAccessMask = src_access;
  b.dstStageMask = dst_stage;
  b.dstAccessMask = dst_access;
  VkDependencyInfo di{};
  di.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
  di.memoryBarrierCount = 1;
  di.pMemoryBarriers = &b;
  ctx.vk.vkCmdPipelineBarrier2(cmd, &di);
}

}  // namespace tressvk::render::compute
