// Internal state of the plugin's handles: assets (static GPU data shared by instances) and instances (dynamic
// state, parameters and the per-frame parameter ring).
#pragma once

#include "core/context.hpp"
#include "core/gpu.hpp"
#include "core/hazards.hpp"
#include "tressvk/model/gpu_layout.hpp"
#include "sim/passes.hpp"

#include <tressvk/asset.hpp>
#include <tressvk/model/model.hpp>
#include <tressvk/model/planner.hpp>

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

struct TvkAsset_T {
  tressvk::Context* ctx = nullptr;
  tressvk::asset::HairAsset cpu;        // kept for group names, bone count and the reference
  tressvk::model::ModelRest rest;   // the model's rest data (double), from which the GPU data is made
  float median_strand_length = 0.0f;
  // The renderer's bound of the groom around the asset origin (render/bounds.cpp, made on first use): the farthest a
  // guide vertex can be (root distance + 1.1 x its rest length) and the longest follow offset, in metres.
  double render_guide_reach = -1.0, render_follow_offset = 0.0;
  // Static buffers, bindings 4..11 of shaders/sim/layout.glsl.
  std::array<tressvk::GpuBuffer, 8> statics{};
  uint32_t users = 1;                   // the host's handle plus one per live instance
  void release();                       // drops one user; frees (deferred) at zero
};

namespace tressvk {
// What tressvk_cmd_simulate needs of a frame's plan besides its GPU form (plan_frame: the planner's substeps are freed
// where the plan is made).
struct PlannedFrame {
  uint32_t steps = 0;
  double h = 0;                        // the plan's step (s): a step rate set after planning applies next frame
  std::array<double, 3> sim_origin{};  // FramePlan::sim_origin
};
}  // namespace tressvk

struct TvkInstance_T {
  tressvk::Context* ctx = nullptr;
  TvkAsset_T* asset = nullptr;
  bool holds_asset = false;             // counted in asset->users (only once handed to the host)
  TvkSimSettings settings{};
  std::vector<TvkSimParams> params;     // one per strand group
  TvkSimFrame frame{};                  // this frame's input (tressvk_set_frame)
  std::vector<TvkBoneMatrix> bones;     // copy of frame.bones
  bool frame_set = false;
  std::unique_ptr<tressvk::model::FramePlanner> planner;
  // tressvk_plan_frame: this frame's plan in its GPU form, made ahead of tressvk_cmd_simulate, which takes it.
  bool planned = false;
  tressvk::PlannedFrame plan;
  tressvk::model::GpuFrame planned_gpu;

  // Dynamic state, bindings 0..3, the counters (binding 15, host-visible) and the guides' anchors (binding 16).
  tressvk::GpuBuffer positions, prev, prevprev, tangents, counters, anchors;
  // Per-frame parameters, bindings 12 (skin), 13 (groups), 14 (steps): one slice per frame in flight, bound with
  // dynamic offsets.
  tressvk::GpuBuffer ring;
  VkDeviceSize slice_size = 0, groups_offset = 0, steps_offset = 0, skin_offset = 0;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;

  std::array<double, 3> sim_origin{};
  std::vector<std::byte> last_step_inputs;  // what the last step run saw (simulate.cpp: a frame is still or not)
  uint64_t still_frames = 0;                // still frames in a row
  uint64_t still_steps = 0;                 // the steps those frames ran (simulate.cpp: a settled still run)
  // Idle instances (simulate.cpp): the first frame of the current still run, and per frame slot the frame (+ 1; 0:
  // none) whose still dispatch the slot's awake word answers for; idle: every guide asleep and nothing moved since.
  uint64_t still_run_first = 0;
  std::vector<uint64_t> awake_probe;
  bool idle = false;
  uint64_t steps = 0, frames = 0;
  uint32_t steps_last_frame = 0;
  // Follow hairs only for the strands the host draws (tressvk_set_draw_strands): draw_strands is the host's count (0:
  // every rendered strand); follows_written the rendered strands whose follows the last frame that ran wrote (every
  // one below it is current), which bounds what the renderer draws.
  uint32_t draw_strands = 0;
  uint32_t follows_written = 0;
  tressvk::HazardTracker hazards;
};

namespace tressvk {

// Bindings 12 (skin), 13 (groups) and 14 (steps) move through the per-frame ring with dynamic offsets.
inline bool is_dynamic_binding(uint32_t b) {
  return b == sim::kBindingSkin || b == sim::kBindingGroups || b == sim::kBindingSteps;
}

// Creates (once) the descriptor set layout and pipeline layout shared by every simulation pipeline.
TvkResult ensure_sim_layouts(Context& ctx);
void destroy_sim_objects(Context& ctx);
// Plans the instance's current frame (validated at tressvk_set_frame) into `gpu`: tressvk_plan_frame's work, and
// tressvk_cmd_simulate's for an instance not planned. Throws what the planner throws.
PlannedFrame plan_frame(TvkInstance_T& inst, model::GpuFrame& gpu);
// Builds the simulation pipelines that simulating `frame` would use for `inst` (tressvk_prewarm_instance).
TvkResult prewarm_sim_pipelines(Context& ctx, const TvkInstance_T& inst, const TvkSimFrame& frame);

}  // namespace tressvk
