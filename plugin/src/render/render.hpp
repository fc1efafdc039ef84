// Internal state of a TvkRenderer: pipelines built on first use per pass variant, descriptor set layouts, and a
// per-frame ring of constant blocks and descriptor pools (slot = context frame % frames_in_flight).
#pragma once

#include "core/context.hpp"
#include "core/gpu.hpp"
#include "render/constants.hpp"

#include <tressvk/render.h>

#include <array>
#include <vector>

struct TvkRenderer_T;

namespace tressvk::render {

// The pipelines a renderer may need; each is created when a draw first asks for it.
enum class PipelineKind : uint32_t {
  shadow = 0,             // depth only, light-facing quads
  core = 1,               // opaque core of the shading pass (depth written)
  fringe = 2,             // blended partial coverage (depth tested, not written)
  core_shadowed = 3,
  fringe_shadowed = 4,
  count = 5
};

namespace compute {
struct State;
void destroy(TvkRenderer_T& r);
}  // namespace compute

}  // namespace tressvk::render

struct TvkRenderer_T {
  tressvk::Context* ctx = nullptr;
  TvkRendererCreateInfo info{};
  uint32_t max_draws = 64;
  VkDeviceSize block_stride = 0;  // DrawConstants rounded up to minUniformBufferOffsetAlignment

  // Set 0 (TVK_DRAW_BINDING_*, gpu_layout.h): 0 constants, 1 positions, 2 tangents, 3 guide info, 4 anchors; the
  // shadowed layout adds 5 (shadow map).
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkDescriptorSetLayout shadowed_set_layout = VK_NULL_HANDLE;
  VkPipelineLayout pipeline_layout = VK_NULL_HANDLE;
  VkPipelineLayout shadowed_pipeline_layout = VK_NULL_HANDLE;
  std::array<VkPipeline, static_cast<size_t>(tressvk::render::PipelineKind::count)> pipelines{};

  // Per frame in flight: a slice of the constant ring and a descriptor pool, both reset when the slot is reused.
  tressvk::GpuBuffer ring;
  std::vector<VkDescriptorPool> pools;
  uint64_t current_frame = ~0ull;
  uint32_t slot = 0;
  uint32_t draws_in_frame = 0;
  uint32_t last_drawn_strands = 0;

  // The compute rasterizer (plugin/src/render/compute/): its per-slot descriptor pools and its state, made on
  // first use.
  std::vector<VkDescriptorPool> compute_pools;
  tressvk::render::compute::State* compute = nullptr;

  void destroy();
};

namespace tressvk::render {

TvkResult create_pipeline(TvkRenderer_T& r, PipelineKind kind);

// Shared by the raster and compute recording calls (draw.cpp).
TvkResult check_draw_info(TvkRenderer_T& r, VkCommandBuffer cmd, const TvkDrawInfo* info, const char* fn);
// Switches to this frame's slot (resetting its descriptor pools) and checks max_draws_per_frame.
TvkResult begin_call(TvkRenderer_T& r, const char* fn);
// The draw's constants: matrices relative to the instance origin, LOD (strands drawn), materials, lights (their
// shadowed flag kept only when `shadowed`), shadow projection.
// The strands a draw with `info` takes by its LOD (eye: lod_view), before the simulation's limit.
uint32_t lod_strands(const TvkDrawInfo* info, const TvkView& lod_view);
TvkResult fill_constants(TvkRenderer_T& r, const TvkDrawInfo* info, bool shadow_pass, bool shadowed, const char* fn,
                         DrawConstants& dc, uint32_t& drawn);
// The radius of a sphere around the instance's simulation origin that holds every strand vertex of its last simulated
// step, in metres (draw.cpp says why it holds); < 0 when no bound is known (a skinned instance).
double hair_bound_radius(const TvkInstance_T& inst);
// Copies the constants into this frame's ring slice; returns their offset in r.ring.
VkDeviceSize store_constants(TvkRenderer_T& r, const DrawConstants& dc);
// One descriptor set of `layout` from `pool` (one of this frame slot's pools, reset when the slot comes round); `call`
// names it in the error.
TvkResult allocate_set(TvkRenderer_T& r, VkDescriptorPool pool, VkDescriptorSetLayout layout, const char* call,
                       VkDescriptorSet& set);
// Bindings 0-4 of every hair drawing set: the draw's constants at `offset` in r.ring, the instance's positions,
// tangents and anchors, the asset's guide info.
std::array<VkDescriptorBufferInfo, 5> hair_buffers(const TvkRenderer_T& r, VkDeviceSize offset,
                                                   const TvkInstance_T& inst);

}  // namespace tressvk::render
