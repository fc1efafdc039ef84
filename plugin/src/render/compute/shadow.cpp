// tressvk_cmd_shadow_hair: hair depth merged into the host's shadow map in compute (copy the rectangle of the map
// the hair can reach this frame to a buffer, keep the nearest of it and the hair per texel, copy it back), so that
// hair shadows the host's meshes without the raster path's quads.
#include "state.hpp"

#include "core/objects.hpp"

#include <algorithm>
#include <cmath>

namespace tressvk::render::compute {

namespace {

struct Rect {
  uint32_t x = 0, y = 0, width = 0, height = 0;
};

// The texels of a width x height map the hair can touch this frame, on the CPU and conservative: the bounding sphere
// of the instance's strands (hair_bound_radius) around its simulation origin, projected through the light's
// view-projection (bounds of its clip coordinates, below), grown by the widest strand's half width in texels as
// shadow_depth.comp computes it (at the smallest w) and 2 texels for its 0.75-texel minimum and rounding, clamped to
// the map. The whole map when no bound is known or the sphere reaches behind the light (w <= 0); empty when it lies
// outside the map or the depth range.
Rect hair_rect(const TvkInstance_T& inst, const TvkView& light, const DrawConstants& dc, uint32_t width,
               uint32_t height) {
  const Rect whole{0, 0, width, height};
  const double radius = hair_bound_radius(inst);
  if (!(radius >= 0.0)) return whole;
  // The light's view-projection relative to the simulation origin, in double (column-major).
  double m[16];
  for (int i = 0; i < 16; ++i) m[i] = light.view_projection[i];
  for (int row = 0; row < 4; ++row)
    m[12 + row] += m[row] * inst.sim_origin[0] + m[4 + row] * inst.sim_origin[1] + m[8 + row] * inst.sim_origin[2];
  // Clip coordinates of the sphere's points lie in [c - radius |row|, c + radius |row|] per row (Cauchy-Schwarz),
  // and x / w is monotonic in x and in w while w > 0: the corners of those intervals bound the sphere's image.
  double c[4], extent[4];
  for (int row = 0; row < 4; ++row) {
    c[row] = m[12 + row];
    extent[row] = radius * std::sqrt(m[row] * m[row] + m[4 + row] * m[4 + row] + m[8 + row] * m[8 + row]);
  }
  const double wmin = c[3] - extent[3], wmax = c[3] + extent[3];
  if (!(wmin > 1e-9)) return whole;
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) {
    const double q[4] = {(c[k] - extent[k]) / wmin, (c[k] - extent[k]) / wmax, (c[k] + extent[k]) / wmin,
                         (c[k] + extent[k]) / wmax};
    lo[k] = std::min({q[0], q[1], q[2], q[3]});
    hi[k] = std::max({q[0], q[1], q[2], q[3]});
  }
  const double zlo = lo[2], zhi = hi[2];
  for (int k = 0; k < 2; ++k) {
    const double size = k == 0 ? width : height;
    lo[k] = (lo[k] * 0.5 + 0.5) * size;
    hi[k] = (hi[k] * 0.5 + 0.5) * size;
  }
  if (zhi < 0.0 || zlo > 1.0) return Rect{};
  float widest = 0.0f;  // root width x LOD widening, metres
  for (const GpuMaterial& mat : dc.materials) widest = std::max(widest, mat.shape[1]);
  const double texels_per_metre = std::sqrt(m[0] * m[0] + m[4] * m[4] + m[8] * m[8]) * 0.5 * width / wmin;
  const double margin = 0.5 * double{widest} * dc.lod[0] * texels_per_metre + 2.0;
  const double size[2] = {double(width), double(height)};
  uint32_t a[2], b[2];
  for (int k = 0; k < 2; ++k) {
    a[k] = static_cast<uint32_t>(std::clamp(std::floor(lo[k] - margin), 0.0, size[k]));
    b[k] = static_cast<uint32_t>(std::clamp(std::ceil(hi[k] + margin), 0.0, size[k]));
  }
  if (b[0] <= a[0] || b[1] <= a[1]) return Rect{};
  return Rect{a[0], a[1], b[0] - a[0], b[1] - a[1]};
}

TvkResult record_shadow(TvkRenderer_T& r, VkCommandBuffer cmd, const TvkShadowRasterInfo* info) {
  Context& ctx = *r.ctx;
  const char* fn = "tressvk_cmd_shadow_hair";
  if (!info || info->struct_size != sizeof(TvkShadowRasterInfo))
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: info is NULL or has a wrong struct_size", fn);
  if (TvkResult res = check_draw_info(r, cmd, info->draw, fn); res != TVK_SUCCESS) return res;
  if (!info->shadow_image) return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: shadow_image is required", fn);
  if (TvkResult res = begin_call(r, fn); res != TVK_SUCCESS) return res;
  if (TvkResult res = ensure_pipelines(r); res != TVK_SUCCESS) return res;
  if (TvkResult res = ensure_shadow_pipeline(r); res != TVK_SUCCESS) return res;
  State& s = *r.compute;
  DrawConstants dc;
  uint32_t drawn = 0;
  if (TvkResult res = fill_constants(r, info->draw, true, false, fn, dc, drawn); res != TVK_SUCCESS) return res;
  const uint32_t width = info->draw->view->width, height = info->draw->view->height;
  // Sized for the whole map, so a rectangle that changes from frame to frame never reallocates.
  const VkDeviceSize bytes = VkDeviceSize{4} * width * height;
  if (TvkResult res = grow(ctx, s.shadow_depth, bytes + 4,
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                               VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                           Memory::device, "hair shadow depth");
      res != TVK_SUCCESS)
    return res;
  s.shadow_counter_offset = bytes;  // the raster call copies the counter into its statistics
  const VkDeviceSize offset = store_constants(r, dc);
  const TvkInstance_T& inst = *info->draw->instance;

  VkDescriptorSet set = VK_NULL_HANDLE;
  if (TvkResult res = allocate_set(r, r.compute_pools[r.slot], s.shadow_set_layout,
                                   "vkAllocateDescriptorSets (hair shadow compute)", set);
      res != TVK_SUCCESS)
    return res;
  const std::array<VkDescriptorBufferInfo, 5> hair = hair_buffers(r, offset, inst);
  const std::array<VkDescriptorBufferInfo, 6> buffers{hair[0], hair[1], hair[2], hair[3], hair[4],
                                                      VkDescriptorBufferInfo{s.shadow_depth.buffer, 0, VK_WHOLE_SIZE}};
  std::array<VkWriteDescriptorSet, 6> writes{};
  for (uint32_t i = 0; i < 6; ++i) {
    writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[i].dstSet = set;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = i == 0 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &buffers[i];
  }
  ctx.vk.vkUpdateDescriptorSets(ctx.info.device, 6, writes.data(), 0, nullptr);

  const uint32_t n = dc.counts[0];
  const uint64_t segments = uint64_t{drawn} * (n - 1);
  const Rect rect = hair_rect(inst, *info->draw->view, dc, width, height);
  const Push push{{width, height, rect.x, rect.y},
                  {rect.width, drawn, rect.height, static_cast<uint32_t>(segments)}, {}};
  VkBufferImageCopy region{};  // the rectangle, packed in the buffer (row length = its width)
  region.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
  region.imageOffset = {static_cast<int32_t>(rect.x), static_cast<int32_t>(rect.y), 0};
  region.imageExtent = {rect.width, rect.height, 1};
  const bool any = rect.width > 0 && rect.height > 0;
  // The map from TRANSFER_SRC_OPTIMAL (read by the copy out, if any) to TRANSFER_DST_OPTIMAL for the copy back (or for
  // the host, which gets it back in that layout either way).
  VkImageMemoryBarrier2 ib{};
  ib.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2;
  ib.srcStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
  ib.srcAccessMask = VK_ACCESS_2_NONE;  // a read before a layout change: an execution dependency is enough
  ib.dstStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
  ib.dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
  ib.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  ib.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  ib.srcQueueFamilyIndex = ib.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  ib.image = info->shadow_image;
  ib.subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
  // With it, in the same dependency: the copy out's buffer writes before the hair shader reads and writes them.
  VkMemoryBarrier2 mb{};
  mb.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2;
  mb.srcStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
  mb.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
  mb.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  mb.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
  VkDependencyInfo dep{};
  dep.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
  dep.memoryBarrierCount = any ? 1u : 0u;
  dep.pMemoryBarriers = &mb;
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &ib;
  const uint32_t timed = ctx.time_begin(cmd);  // the whole call: copy out, hair depth, copy back
  if (!any) {  // the hair cannot reach the map: only the layout the contract promises
    ctx.vk.vkCmdPipelineBarrier2(cmd, &dep);
    ctx.time_end(cmd, timed, "render.shadow");
    r.last_drawn_strands = drawn;
    return TVK_SUCCESS;
  }
  uint32_t part = ctx.time_begin(cmd);  // and each of the three
  // The previous frame's copy back read the buffer (and its copy out wrote it): the copy out waits for them.
  memory_barrier(ctx, cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  ctx.vk.vkCmdCopyImageToBuffer(cmd, info->shadow_image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, s.shadow_depth.buffer,
                                1, &region);
  ctx.vk.vkCmdFillBuffer(cmd, s.shadow_depth.buffer, bytes, 4, 0);  // samples outside the rectangle
  ctx.vk.vkCmdPipelineBarrier2(cmd, &dep);
  ctx.time_end(cmd, part, "render.shadow_copy_out");
  part = ctx.time_begin(cmd);
  ctx.vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.shadow);
  ctx.vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.shadow_layout, 0, 1, &set, 0, nullptr);
  ctx.vk.vkCmdPushConstants(cmd, s.shadow_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
  ctx.vk.vkCmdDispatch(cmd, std::max<uint32_t>(1, static_cast<uint32_t>((segments + 63) / 64)), 1, 1);
  // The hair's depths before the copy back reads them (and before the next frame's copy out writes them).
  memory_barrier(ctx, cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                 VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT);
  ctx.time_end(cmd, part, "render.shadow_hair");
  part = ctx.time_begin(cmd);
  ctx.vk.vkCmdCopyBufferToImage(cmd, s.shadow_depth.buffer, info->shadow_image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                1, &region);
  ctx.time_end(cmd, part, "render.shadow_copy_back");
  ctx.time_end(cmd, timed, "render.shadow");
  r.last_drawn_strands = drawn;
  return TVK_SUCCESS;
}

}  // namespace

}  // namespace tressvk::render::compute

extern "C" {

TvkResult tressvk_cmd_shadow_hair(TvkRenderer renderer, VkCommandBuffer command_buffer,
                                  const TvkShadowRasterInfo* info) {
  if (!renderer) return TVK_ERROR_INVALID_ARGUMENT;
  return tressvk::render::compute::record_shadow(*renderer, command_buffer, info);
}

}  // extern "C"
