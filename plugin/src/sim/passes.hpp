// The simulation pass table: what each compute pass is, what it touches, and when it runs. The host code
// (pipelines, descriptor sets, barriers, the pass list) is driven entirely by this table, so a pass's buffers,
// dispatch size and run rule live in one place next to the shaders.
//
// Recording order per frame: for each substep: integrate, [vsp], [local_shape], length; then once: [follow].
// Barriers between passes follow from `reads`/`writes` (bit b = binding b of gpu_layout.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tressvk/sim_types.h"

#include "tressvk/model/gpu_layout.hpp"

namespace tressvk::sim {

enum class PassId : uint32_t { kIntegrate, kVsp, kLocalShape, kLength, kFollow, kFrame /* fused.hpp */ };

enum class Granularity : uint32_t {
  kGuideVertex,   // one thread per guide vertex: padded(G)*N threads, thread i = element i of the blocked layout
  kGuide,         // one thread per guide: G threads (a serial walk along the strand)
  kFollowVertex,  // one thread per follow vertex: padded(G*K)*N threads, in the blocked order of the follows
};

enum class Frequency : uint32_t {
  kPerSubstep,  // recorded once per substep, push constants select the substep
  kPerFrame,    // recorded once after the last substep (push constants of the last substep)
};

constexpr uint32_t binding_bit(uint32_t binding) { return 1u << binding; }

struct PassInfo {
  PassId id;
  const char* base_name;       // "integrate", "vsp", "local_shape", "length", "follow"
  const uint32_t* spirv;       // embedded SPIR-V (tressvk_sim_spirv.h)
  size_t spirv_bytes;
  Granularity granularity;
  Frequency frequency;
  uint32_t reads;              // binding bits read
  uint32_t writes;             // binding bits written
  uint32_t features_used;      // Feature bits that change this pass's pipeline (others are masked off)
  bool uses_capsule_count;     // CAPSULE_COUNT specialisation matters
};

// All five passes, in recording order.
std::span<const PassInfo> pass_table();
const PassInfo& pass_info(PassId id);

// What one instance's frame needs, derived from its inputs.
struct SceneTerms {
  bool vsp = false;            // some group has vsp_coefficient > 0
  bool local_shape = false;    // some group has local_stiffness > 0 and local_iterations > 0
  bool follow = false;         // the asset has follow hairs (K > 0)
  uint32_t features = 0;       // Feature bits (global shape, wind, collision, skinning, max speed, pinned tips)
  uint32_t capsule_count = 0;  // 0..8 (0 unless collision)
};

// Rules: VSP off in every group => no vsp pass; local stiffness or iterations 0 in every group => no
// local_shape pass; K = 0 => no follow pass; wind strength 0 or zero direction => no wind term; no capsules =>
// no collision term; max_speed 0 in every group => no clamp; global stiffness or range 0 in every group => no
// global shape term; no bone matrices => rigid transform only.
// pinned_tips: the asset has a strand pinned at its tip with free vertices (it compiles the length pass's
// tridiagonal solve in; without such strands the pipeline carries none of it).
SceneTerms scene_terms(std::span<const TvkSimParams> groups, const TvkSimFrame& frame, uint32_t follow_per_guide,
                       bool pinned_tips = false);

struct PassUse {
  const PassInfo* info;
  std::string name;            // e.g. "integrate+global", "length+wind+collision+clamp" (for the pass list)
  uint32_t features;           // terms.features & info->features_used: the FEATURES specialisation constant
  uint32_t capsule_count;      // the CAPSULE_COUNT specialisation constant (0 where unused)
};

// The passes an instance records for one substep/frame, in order (per-substep ones first, then per-frame).
std::vector<PassUse> passes_for(const SceneTerms& terms);

// Workgroups to dispatch for a pass: the thread count of its granularity rounded up (per-vertex passes cover whole
// strand blocks; threads of padding strands and past the end return at once).
uint32_t dispatch_groups(Granularity granularity, uint32_t guide_count, uint32_t vertices_per_strand,
                         uint32_t follow_per_guide, uint32_t workgroup_size);

}  // namespace tressvk::sim
