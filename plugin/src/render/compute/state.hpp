// The compute strand rasterizer's state inside a TvkRenderer: pipelines (made on first use), buffers (grown to
// the largest view and groom seen, never per frame) and the capture/statistics readback. Bindings and push
// constants match shaders/render/compute/raster_layout.glsl.
#pragma once

#include "render/render.hpp"

#include <array>
#include <cstdint>

namespace tressvk::render::compute {

enum Binding : uint32_t {
  kConstants = 0, kPositions = 1, kTangents = 2, kGuideInfo = 3, kAnchors = 4, kShadowMap = 5, kHostDepth = 6,
  kVerts = 7, kTiles = 8, kEntries = 9, kCounters = 10, kImage = 11, kCapture = 12, kDom = 13, kSplitItems = 14,
  kPartials = 15, kBindingCount = 16
};

enum class Pass : uint32_t {
  project = 0, tile_depth, count, scan, scatter, fine, dom_front, dom_layers, fine_per_fragment, fine_split,
  fine_split_per_fragment, scan_top, shade, dom_clean, pass_count
};

struct Push {
  uint32_t size[4];    // width, height, tiles x, tiles y
  uint32_t params[4];  // entry capacity, strands drawn, flags, segments
  uint32_t split[4];   // split work item slots, unused x 3
};

constexpr uint32_t kTile = 8;
// fine.comp's specialization constants: entries a tile holds in shared memory per load (kCap; its histogram of 256
// bins shares their space), the most entries a tile ranks whole without the histogram (kSlice), and fragments in
// the per-pixel reorder window (kReorder, 0 off). 512 entries per load, or 256 ranked whole, measured slower.
constexpr uint32_t kSliceCapacity = 256;
constexpr uint32_t kSliceEntries = 64;
static_assert(kSliceCapacity >= 256 && kSliceCapacity <= 1024 && kSliceEntries <= kSliceCapacity,
              "fine.comp: kBins <= kCap <= 64 * kMaxRanks, kSlice <= kCap");
constexpr uint32_t kReorderWindow = 4;
// fine.comp: covering fragments a pixel still takes once opaque, so the window can put a nearer later one first.
constexpr uint32_t kSettleFragments = 4;
// Over-full tiles (raster_layout.glsl): more than kSplitAt entries (more than kSplitFewAt when at most kSplitFew
// tiles of the call have that many) are composited by ceil(count / kSplit)
// workgroups of the split pass, which holds kSplitCapacity entries in shared memory (one load for a share of
// kSplit entries); at most kSplitSlots work items per call (a tile that does not fit stays whole).
constexpr uint32_t kSplitAt = 8192;
constexpr uint32_t kSplitFewAt = 2048;
constexpr uint32_t kSplitFew = 512;
constexpr uint32_t kSplit = 1024;
constexpr uint32_t kSplitCapacity = 1024;
static_assert(kSplitCapacity >= 256 && kSplitCapacity <= 1024, "fine.comp: kBins <= kCap <= 64 * kMaxRanks");
constexpr uint32_t kSplitSlots = 65535;
constexpr uint32_t kCounterCount = 8;
constexpr uint32_t kDomSize = 512;   // deep opacity map texels per side (raster_layout.glsl)
constexpr uint32_t kDomLayers = 4;
static_assert(kDomLayers == 4, "shade.glsl reads a texel's layers as one uvec4 (raster_layout.glsl, dom_layers)");
constexpr uint32_t kFlagShadowed = 4;
constexpr uint32_t kFlagPerFragment = 8;  // raster_layout.glsl: TVK_RASTER_SHADE_PER_FRAGMENT
constexpr uint32_t kFlagSplitDense = 16;  // raster_layout.glsl: TVK_RASTER_SPLIT_AS_DENSE

struct State {
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  std::array<VkPipeline, static_cast<size_t>(Pass::pass_count)> pipelines{};
  VkSampler sampler = VK_NULL_HANDLE;  // nearest, for texelFetch of the host's depth and shadow map

  VkDescriptorSetLayout composite_set_layout = VK_NULL_HANDLE;
  VkPipelineLayout composite_layout = VK_NULL_HANDLE;
  VkPipeline composite = VK_NULL_HANDLE;

  // tressvk_cmd_shadow_hair: its own layout (constants, strands, a copy of the host's shadow map) and pipeline.
  VkDescriptorSetLayout shadow_set_layout = VK_NULL_HANDLE;
  VkPipelineLayout shadow_layout = VK_NULL_HANDLE;
  VkPipeline shadow = VK_NULL_HANDLE;
  GpuBuffer shadow_depth;  // the copied rectangle, then (after the whole map's texels) the outside-samples counter
  VkDeviceSize shadow_counter_offset = 0;  // where that counter is (0: no shadow call yet)

  GpuBuffer verts, tiles, entries, counters, image, capture_depth, dom;
  // The deep opacity map is not known to be clear (new, or last read by a per-fragment fine pass, which the
  // scatter pass cannot clear it before): the next raster call clears it with transfer fills first.
  bool dom_dirty = true;
  GpuBuffer split_items, partials;  // over-full tiles' work items (and the split pass's dispatch), partial layers
  uint32_t entry_capacity = 0;
  uint32_t split_slots = 0;     // capacity of `partials` in work items
  uint32_t image_pixels = 0;    // capacity of `image` in pixels
  uint32_t width = 0, height = 0;  // of the last raster call (the composite draws this)
  GpuBuffer stats_readback;     // counters of the last call
  GpuBuffer capture_verts, capture_host_depth, capture_image;  // host-readable copies (TVK_RASTER_CAPTURE)
  TvkRasterCapture capture{};
  bool captured = false;
};

// Creates the layouts, sampler and compute pipelines on first use.
TvkResult ensure_pipelines(TvkRenderer_T& r);
TvkResult ensure_composite_pipeline(TvkRenderer_T& r);
TvkResult ensure_shadow_pipeline(TvkRenderer_T& r);
TvkResult grow(Context& ctx, GpuBuffer& buffer, VkDeviceSize size, VkBufferUsageFlags usage, Memory memory,
               const char* name);
// Grows the buffers for a view of width x height and `vertices` strand vertices / `segments` segments (twice the
// vertex data when shading per fragment: the point and tangent follow the screen data).
TvkResult ensure_buffers(TvkRenderer_T& r, uint32_t width, uint32_t height, uint64_t vertices, uint64_t segments,
                         bool capture, bool per_fragment);
uint64_t memory_bytes(const State& s);
// Records one VkMemoryBarrier2 from (src_stage, src_access) to (dst_stage, dst_access).
void memory_barrier(Context& ctx, VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                    VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access);

}  // namespace tressvk::render::compute
