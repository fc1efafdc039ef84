// tressvk_cmd_raster_hair: the compute strand rasterizer's passes, recorded outside the host's passes, in five
// dependent steps of passes that run side by side:
//   [deep opacity map: nearest hair | tile host depth (+ zeroed counts) | vertex projection]
//   -> [deep opacity map: fibre layers | count] -> [vertex shading | scan] -> scan top -> scatter (+ the deep
//   opacity map cleared for the next call) -> [fine split of a few heavy tiles | fine (sort + composite per tile,
//   the heaviest tiles first) | fine split of a dense groom's over-full tiles] (the split dispatches are indirect,
//   one of them empty)
// with a compute-to-compute memory barrier between steps (docs/rendering.md, "The compute path").
#include "state.hpp"

#include "core/objects.hpp"

#include <algorithm>

namespace tressvk::render::compute {

namespace {

constexpr VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkAccessFlags2 kStorageRW = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;

void compute_to_compute(Context& ctx, VkCommandBuffer cmd) {
  memory_barrier(ctx, cmd, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, kCompute, kStorageRW);
}

uint32_t groups(uint64_t items, uint32_t size) { return static_cast<uint32_t>((items + size - 1) / size); }

TvkResult record(TvkRenderer_T& r, VkCommandBuffer cmd, const TvkRasterInfo* info) {
  Context& ctx = *r.ctx;
  const char* fn = "tressvk_cmd_raster_hair";
  if (!info || info->struct_size != sizeof(TvkRasterInfo))
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: info is NULL or has a wrong struct_size", fn);
  if (TvkResult res = check_draw_info(r, cmd, info->draw, fn); res != TVK_SUCCESS) return res;
  if (!info->depth_view)
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: depth_view (the host's opaque depth) is required", fn);
  const TvkDrawInfo& draw = *info->draw;
  const bool capture = (info->flags & TVK_RASTER_CAPTURE) != 0;
  const bool per_fragment = (info->flags & TVK_RASTER_SHADE_PER_FRAGMENT) != 0;
  if (TvkResult res = begin_call(r, fn); res != TVK_SUCCESS) return res;
  if (TvkResult res = ensure_pipelines(r); res != TVK_SUCCESS) return res;
  State& s = *r.compute;

  const bool shadowed = draw.shadow && draw.shadow->depth_view;
  DrawConstants dc;
  uint32_t drawn = 0;
  if (TvkResult res = fill_constants(r, &draw, false, shadowed, fn, dc, drawn); res != TVK_SUCCESS) return res;
  const TvkInstance_T& inst = *draw.instance;
  const TvkAsset_T& asset = *inst.asset;
  const uint32_t n = dc.counts[0];
  const uint32_t total = asset.cpu.total_strands();
  const uint32_t width = draw.view->width, height = draw.view->height;
  // Sized for the whole groom (not this frame's LOD), so a changing LOD never reallocates.
  if (TvkResult res = ensure_buffers(r, width, height, uint64_t{total} * n, uint64_t{total} * (n - 1), capture,
                                      per_fragment);
      res != TVK_SUCCESS)
    return res;
  const VkDeviceSize constants_offset = store_constants(r, dc);

  // Descriptors.
  VkDescriptorSet set = VK_NULL_HANDLE;
  if (TvkResult res = allocate_set(r, r.compute_pools[r.slot], s.set_layout, "vkAllocateDescriptorSets (hair compute)",
                                   set);
      res != TVK_SUCCESS)
    return res;
  std::array<VkDescriptorBufferInfo, kBindingCount> buffers{};
  const std::array<VkDescriptorBufferInfo, 5> hair = hair_buffers(r, constants_offset, inst);
  std::copy(hair.begin(), hair.end(), buffers.begin());  // kConstants .. kAnchors
  buffers[kVerts] = {s.verts.buffer, 0, VK_WHOLE_SIZE};
  buffers[kTiles] = {s.tiles.buffer, 0, VK_WHOLE_SIZE};
  buffers[kEntries] = {s.entries.buffer, 0, VK_WHOLE_SIZE};
  buffers[kCounters] = {s.counters.buffer, 0, VK_WHOLE_SIZE};
  buffers[kImage] = {s.image.buffer, 0, VK_WHOLE_SIZE};
  buffers[kCapture] = {s.capture_depth.buffer, 0, VK_WHOLE_SIZE};
  buffers[kDom] = {s.dom.buffer, 0, VK_WHOLE_SIZE};
  buffers[kSplitItems] = {s.split_items.buffer, 0, VK_WHOLE_SIZE};
  buffers[kPartials] = {s.partials.buffer, 0, VK_WHOLE_SIZE};
  const VkDescriptorImageInfo depth_image{s.sampler, info->depth_view, info->depth_layout};
  const VkDescriptorImageInfo shadow_image =
      shadowed ? VkDescriptorImageInfo{s.sampler, draw.shadow->depth_view, draw.shadow->layout} : depth_image;
  std::array<VkWriteDescriptorSet, kBindingCount> writes{};
  for (uint32_t i = 0; i < kBindingCount; ++i) {
    writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[i].dstSet = set;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    if (i == kConstants) {
      writes[i].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
      writes[i].pBufferInfo = &buffers[i];
    } else if (i == kShadowMap || i == kHostDepth) {
      writes[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
      writes[i].pImageInfo = i == kShadowMap ? &shadow_image : &depth_image;
    } else {
      writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
      writes[i].pBufferInfo = &buffers[i];
    }
  }
  ctx.vk.vkUpdateDescriptorSets(ctx.info.device, kBindingCount, writes.data(), 0, nullptr);

  const uint32_t tiles_x = (width + kTile - 1) / kTile, tiles_y = (height + kTile - 1) / kTile;
  const uint64_t tile_count = uint64_t{tiles_x} * tiles_y;
  const uint64_t segments = uint64_t{drawn} * (n - 1);
  Push push{{width, height, tiles_x, tiles_y},
            {s.entry_capacity, drawn,
             (info->flags & (TVK_RASTER_CAPTURE | TVK_RASTER_REVERSE_STRANDS)) | (shadowed ? kFlagShadowed : 0u) |
                 (per_fragment ? kFlagPerFragment : 0u) |
                 ((info->flags & TVK_RASTER_SPLIT_AS_DENSE) != 0 ? kFlagSplitDense : 0u),
             static_cast<uint32_t>(segments)},
            {s.split_slots, 0, 0, 0}};

  // The previous frame's raster and composite calls used the same buffers: wait for them (and make their
  // writes available) before this call writes them.
  memory_barrier(ctx, cmd,
                 kCompute | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                     VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                 VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                 kCompute | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                 kStorageRW | VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
  uint32_t timed = ctx.time_begin(cmd);  // per-pass GPU times (tressvk_get_pass_timings) when timestamps are on
  if (shadowed && s.dom_dirty) {
    // A new map, or one a per-fragment fine pass read last: clear it (otherwise the last scatter pass did).
    const VkDeviceSize dom_texels = VkDeviceSize{kDomSize} * kDomSize;
    ctx.vk.vkCmdFillBuffer(cmd, s.dom.buffer, 0, 4 * dom_texels, 0x7f800000u);  // nearest hair: +infinity
    ctx.vk.vkCmdFillBuffer(cmd, s.dom.buffer, 4 * dom_texels, 4 * dom_texels * kDomLayers, 0);
    memory_barrier(ctx, cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, kCompute,
                   kStorageRW);
  }
  // Beside the scatter pass, once the vertex shading has read it, the deep opacity map is cleared for the next
  // call; shaded per fragment the fine pass reads it after that, so the next call clears it with fills instead.
  const bool clean_dom = shadowed && !per_fragment;
  if (shadowed) s.dom_dirty = !clean_dom;
  // The fine pass's list of tiles with entries and its dispatch size (scan.comp, listed by the scatter pass).
  const VkDeviceSize tile_list = 4 * (6 * VkDeviceSize{tile_count} + 2 * ((tile_count + 1023) / 1024));
  const auto next = [&](const char* finished) {  // closes the timed step `finished`, opens the next
    ctx.time_end(cmd, timed, finished);
    timed = ctx.time_begin(cmd);
  };

  ctx.vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.layout, 0, 1, &set, 0, nullptr);
  ctx.vk.vkCmdPushConstants(cmd, s.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
  const auto bind = [&](Pass p) {
    ctx.vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipelines[static_cast<size_t>(p)]);
  };
  // Step 1: the nearest hair of the deep opacity map, the tiles' farthest host depth (and the zeroed counts), the
  // vertices' projection; no barrier between them (each writes what the others do not touch).
  const uint32_t segment_groups = std::max(1u, groups(segments, 64));
  if (shadowed) {
    bind(Pass::dom_front);
    ctx.vk.vkCmdDispatch(cmd, segment_groups, 1, 1);
  }
  bind(Pass::tile_depth);
  ctx.vk.vkCmdDispatch(cmd, (tiles_x + 7) / 8, tiles_y, 1);  // a row of 8 tiles per workgroup
  bind(Pass::project);
  ctx.vk.vkCmdDispatch(cmd, groups(uint64_t{drawn} * n, 64), 1, 1);
  compute_to_compute(ctx, cmd);
  next("render.project");
  // Step 2: the fibre layers of the deep opacity map beside the count.
  if (shadowed) {
    bind(Pass::dom_layers);
    ctx.vk.vkCmdDispatch(cmd, segment_groups, 1, 1);
  }
  bind(Pass::count);
  ctx.vk.vkCmdDispatch(cmd, segment_groups, 1, 1);
  compute_to_compute(ctx, cmd);
  next("render.bin_count");
  // Step 3: the vertex shading (it reads the deep opacity map) beside the scan's blocks; then the scan's top.
  bind(Pass::shade);
  ctx.vk.vkCmdDispatch(cmd, groups(uint64_t{drawn} * n, 64), 1, 1);
  bind(Pass::scan);  // offsets within blocks of 1024 tiles, then the blocks' offsets
  ctx.vk.vkCmdDispatch(cmd, static_cast<uint32_t>((tile_count + 1023) / 1024), 1, 1);
  compute_to_compute(ctx, cmd);
  bind(Pass::scan_top);
  ctx.vk.vkCmdDispatch(cmd, 1, 1, 1);
  // The scan also wrote the split pass's indirect dispatch size.
  memory_barrier(ctx, cmd, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                 kCompute | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, kStorageRW | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
  next("render.shade_scan");
  bind(Pass::scatter);
  ctx.vk.vkCmdDispatch(cmd, segment_groups, 1, 1);
  if (clean_dom) {  // 64 words per thread
    bind(Pass::dom_clean);
    ctx.vk.vkCmdDispatch(cmd, kDomSize * kDomSize * (1 + kDomLayers) / (64 * 64), 1, 1);
  }
  // The fine pass reads the tiles buffer the scatter wrote (the packed list) also as its indirect dispatch (written
  // by the scan; the buffer is one resource to the barrier).
  memory_barrier(ctx, cmd, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                 kCompute | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, kStorageRW | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
  next("render.bin_scatter");
  // The split pass before the fine pass when it splits a few tiles, after it when many (scan.comp chose: one of the
  // two indirect dispatches is empty). No barrier between them: the split pass composites only the tiles the fine
  // pass skips (and its own partial layers).
  const Pass split = per_fragment ? Pass::fine_split_per_fragment : Pass::fine_split;
  bind(split);
  ctx.vk.vkCmdDispatchIndirect(cmd, s.split_items.buffer, 16);
  bind(per_fragment ? Pass::fine_per_fragment : Pass::fine);
  if (capture) {
    ctx.vk.vkCmdDispatch(cmd, tiles_x, tiles_y, 1);  // every tile: the captured layer and host depth are whole
  } else {
    ctx.vk.vkCmdDispatchIndirect(cmd, s.tiles.buffer, tile_list);  // the tiles with entries (scan.comp)
  }
  bind(split);
  ctx.vk.vkCmdDispatchIndirect(cmd, s.split_items.buffer, 0);
  ctx.time_end(cmd, timed, "render.fine");
  // The layer for the composite call's fragment shader; the counters (and captures) for the copies below.
  memory_barrier(ctx, cmd, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                 VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                     VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                 VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                     VK_ACCESS_2_TRANSFER_READ_BIT);
  const VkBufferCopy counters{0, 0, 4 * kCounterCount};
  ctx.vk.vkCmdCopyBuffer(cmd, s.counters.buffer, s.stats_readback.buffer, 1, &counters);
  // The last shadow call's count of samples outside its rectangle (its compute -> transfer barrier made it
  // available; this call's first barrier orders the copy after it), read with the other counters.
  if (s.shadow_counter_offset) {
    const VkBufferCopy outside{s.shadow_counter_offset, 4 * kCounterCount, 4};
    ctx.vk.vkCmdCopyBuffer(cmd, s.shadow_depth.buffer, s.stats_readback.buffer, 1, &outside);
  }
  if (capture) {
    const uint64_t pixels = uint64_t{width} * height;
    const VkBufferCopy verts{0, 0, 32 * uint64_t{drawn} * n};
    const VkBufferCopy depth{0, 0, 4 * pixels};
    const VkBufferCopy layer{0, 0, 8 * pixels};
    ctx.vk.vkCmdCopyBuffer(cmd, s.verts.buffer, s.capture_verts.buffer, 1, &verts);
    ctx.vk.vkCmdCopyBuffer(cmd, s.capture_depth.buffer, s.capture_host_depth.buffer, 1, &depth);
    ctx.vk.vkCmdCopyBuffer(cmd, s.image.buffer, s.capture_image.buffer, 1, &layer);
    s.capture = TvkRasterCapture{width, height, n, drawn, nullptr, nullptr, nullptr};
    s.captured = true;
  }
  memory_barrier(ctx, cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                 VK_ACCESS_2_HOST_READ_BIT);
  s.width = width;
  s.height = height;
  r.last_drawn_strands = drawn;
  return TVK_SUCCESS;
}

}  // namespace

}  // namespace tressvk::render::compute

extern "C" {

TvkResult tressvk_cmd_raster_hair(TvkRenderer renderer, VkCommandBuffer command_buffer, const TvkRasterInfo* info) {
  if (!renderer) return TVK_ERROR_INVALID_ARGUMENT;
  return tressvk::render::compute::record(*renderer, command_buffer, info);
}

}  // extern "C"
