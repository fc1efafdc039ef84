// tressvk_cmd_composite_hair: the hair layer of the last raster call blended over the host's colour target, a
// quad per tile with hair (composite.vert; an indirect draw the raster call's fine pass sized) inside the host's
// pass.
#include "state.hpp"

namespace tressvk::render::compute {

namespace {

TvkResult record_composite(TvkRenderer_T& r, VkCommandBuffer cmd) {
  Context& ctx = *r.ctx;
  const char* fn = "tressvk_cmd_composite_hair";
  if (!cmd) return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: command buffer is NULL", fn);
  if (const TvkResult lost = ctx.require_device(fn); lost != TVK_SUCCESS) return lost;
  if (!r.compute || r.compute->width == 0)
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: no tressvk_cmd_raster_hair was recorded before", fn);
  if (TvkResult res = begin_call(r, fn); res != TVK_SUCCESS) return res;
  if (TvkResult res = ensure_composite_pipeline(r); res != TVK_SUCCESS) return res;
  State& s = *r.compute;
  VkDescriptorSet set = VK_NULL_HANDLE;
  if (TvkResult res = allocate_set(r, r.compute_pools[r.slot], s.composite_set_layout,
                                   "vkAllocateDescriptorSets (hair composite)", set);
      res != TVK_SUCCESS)
    return res;
  const VkDescriptorBufferInfo image{s.image.buffer, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet w{};
  w.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
  w.dstSet = set;
  w.dstBinding = 0;
  w.descriptorCount = 1;
  w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  w.pBufferInfo = &image;
  ctx.vk.vkUpdateDescriptorSets(ctx.info.device, 1, &w, 0, nullptr);
  const uint32_t size[4] = {s.width, s.height, 0, 0};
  ctx.vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, s.composite);
  ctx.vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, s.composite_layout, 0, 1, &set, 0, nullptr);
  ctx.vk.vkCmdPushConstants(cmd, s.composite_layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                            sizeof(size), size);
  const uint32_t timed = ctx.time_begin(cmd);
  // The VkDrawIndirectCommand after the layer's pixels (fine.comp: 6 vertices per tile with hair).
  ctx.vk.vkCmdDrawIndirect(cmd, s.image.buffer, 8 * VkDeviceSize{s.width} * s.height, 1, 16);
  ctx.time_end(cmd, timed, "render.composite");
  return TVK_SUCCESS;
}

}  // namespace

}  // namespace tressvk::render::compute

extern "C" {

TvkResult tressvk_cmd_composite_hair(TvkRenderer renderer, VkCommandBuffer command_buffer) {
  if (!renderer) return TVK_ERROR_INVALID_ARGUMENT;
  return tressvk::render::compute::record_composite(*renderer, command_buffer);
}

TvkResult tressvk_get_raster_stats(TvkRenderer renderer, TvkRasterStats* out) {
  using namespace tressvk::render::compute;
  if (!renderer || !out) return TVK_ERROR_INVALID_ARGUMENT;
  *out = TvkRasterStats{};
  State* s = renderer->compute;
  if (!s || !s->stats_readback) return TVK_SUCCESS;
  tressvk::Context& ctx = *renderer->ctx;
  vmaInvalidateAllocation(ctx.allocator, s->stats_readback.allocation, 0, VK_WHOLE_SIZE);
  const auto* c = static_cast<const uint32_t*>(s->stats_readback.mapped);
  out->entries_requested = c[0];
  out->dropped_entries = c[1];
  out->segments_binned = c[2];
  out->dropped_slice_entries = c[3];
  out->fragments = c[4];
  out->hair_pixels = c[5];
  out->sliced_tiles = c[6];
  out->split_tiles = c[7];
  out->shadow_samples_outside = c[kCounterCount];  // the shadow call's counter (raster.cpp copies it)
  out->memory_bytes = memory_bytes(*s);
  out->entry_capacity = s->entry_capacity;
  out->slice_capacity = kSliceCapacity;
  return TVK_SUCCESS;
}

TvkResult tressvk_get_raster_capture(TvkRenderer renderer, TvkRasterCapture* out) {
  using namespace tressvk::render::compute;
  if (!renderer || !out) return TVK_ERROR_INVALID_ARGUMENT;
  State* s = renderer->compute;
  tressvk::Context& ctx = *renderer->ctx;
  if (!s || !s->captured)
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_get_raster_capture: no raster call with TVK_RASTER_CAPTURE");
  for (const tressvk::GpuBuffer* b : {&s->capture_verts, &s->capture_host_depth, &s->capture_image})
    vmaInvalidateAllocation(ctx.allocator, b->allocation, 0, VK_WHOLE_SIZE);
  *out = s->capture;
  out->vertices = static_cast<const float*>(s->capture_verts.mapped);
  out->host_depth = static_cast<const float*>(s->capture_host_depth.mapped);
  out->layer = static_cast<const uint16_t*>(s->capture_image.mapped);
  return TVK_SUCCESS;
}

}  // extern "C"
