// tressvk_cmd_shadow_hair: hair depth merged into the host's shadow map in compute (copy the map to a buffer,
// keep the nearest of it and the hair per texel, copy it back), so that hair shadows the host's meshes without
// the raster path's quads.
#include "state.hpp"

#include "core/objects.hpp"

#include <algorithm>

namespace tressvk::render::compute {

namespace {

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
  const VkDeviceSize bytes = VkDeviceSize{4} * width * height;
  if (TvkResult res = grow(ctx, s.shadow_depth, bytes,
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                               VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                           Memory::device, "hair shadow depth");
      res != TVK_SUCCESS)
    return res;
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
  const Push push{{width, height, 0, 0}, {0, drawn, 0, static_cast<uint32_t>(segments)}, {}};
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
  region.imageExtent = {width, height, 1};
  // The previous frame's copies used the buffer; then the map into it, the hair on top, and back.
  const uint32_t timed = ctx.time_begin(cmd);  // the whole call: copy out, hair depth, copy back
  uint32_t part = ctx.time_begin(cmd);         // and each of the three
  memory_barrier(ctx, cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
          VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
  ctx.vk.vkCmdCopyImageToBuffer(cmd, info->shadow_image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, s.shadow_depth.buffer,
                                1, &region);
  // The map from TRANSFER_SRC_OPTIMAL (read above) to TRANSFER_DST_OPTIMAL for the copy back.
  VkImageMemoryBarrier2 ib{};
  ib.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2;
  ib.srcStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
  ib.srcAccessMask = VK_ACCESS_2_NONE;
  ib.dstStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
  ib.dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
  ib.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  ib.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  ib.srcQueueFamilyIndex = ib.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  ib.image = info->shadow_image;
  ib.subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
  VkDependencyInfo dep{};
  dep.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &ib;
  ctx.vk.vkCmdPipelineBarrier2(cmd, &dep);
  ctx.time_end(cmd, part, "render.shadow_copy_out");
  part = ctx.time_begin(cmd);
  memory_barrier(ctx, cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
          VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  ctx.vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.shadow);
  ctx.vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.shadow_layout, 0, 1, &set, 0, nullptr);
  ctx.vk.vkCmdPushConstants(cmd, s.shadow_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
  ctx.vk.vkCmdDispatch(cmd, std::max<uint32_t>(1, static_cast<uint32_t>((segments + 63) / 64)), 1, 1);
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
