// The fused frame kernel (shaders/sim/frame.glsl): one dispatch per instance per frame running every substep and
// every pass the scene needs, the strand's state on chip. It is the default simulation path; the pass-per-dispatch
// path (passes.hpp, one dispatch per pass per substep) stays behind TRESSVK_SIM_PATH=passes as a debugging aid that
// times each pass on its own (docs/simulation.md).
#pragma once

#include <cstdint>

#include "sim/passes.hpp"

namespace tressvk::sim {

enum class SimPath : uint32_t {
  kAuto,         // the default: kLanes where ftl_lanes_by_default (small grooms), else kFused
  kLanes,        // the lane kernel (frame_lanes_ftl*.comp; shared-memory exchange where the subgroup is too small),
                 // except for strands pinned at their tip (kFused)
  kFused,        // frame.comp: one thread per strand, the strand in private arrays
  kFusedShared,  // frame_shared.comp: the strand block in shared memory (where it fits, else kFused)
  kPasses,       // one dispatch per pass per substep
};

// TRESSVK_SIM_PATH = "lanes", "fused", "fused-shared" or "passes"; read once per process. Anything else: kAuto.
SimPath sim_path_from_environment();

// Shared memory the shared-memory variant needs for N vertices per strand (positions and history; VSP's second
// history lives in registers).
uint32_t frame_shared_bytes(uint32_t vertices_per_strand, bool vsp);

// The frame pass of a scene: FEATURES = the scene's feature bits plus kFeatureVsp / kFeatureLocalShape.
// shared: the shared-memory variant (the caller checked that it fits).
PassUse frame_pass_use(const SceneTerms& terms, bool shared);

// Workgroups of the frame pass: one per strand block of 32 guides.
uint32_t frame_dispatch_groups(uint32_t guide_count);

// The lane-parallel frame kernel (frame_lanes.glsl), one lane per vertex, for either model: follow-the-leader
// (lanes_ftl.glsl) or compliant (lanes_compliant.glsl, TRESSVK_SIM_MODEL=compliant, which always takes it). Two
// variants each: subgroup (a strand is a cluster of lanes of one subgroup, values move by shuffles;
// frame_lanes*_subgroup.comp) where lanes_fit_subgroup, else shared (one strand per workgroup, values through shared
// memory). TRESSVK_SIM_LANES=shared (read once per process) keeps the shared variant everywhere.
// It records as the frame pass (PassId::kFrame) with its own pipeline.
enum class LanesBackend { kAuto, kShared };
LanesBackend lanes_backend_from_environment();
// The power of two >= N fits the subgroup, and compute shaders may shuffle and vote.
bool lanes_fit_subgroup(uint32_t vertices_per_strand, uint32_t subgroup_size, bool shuffle_compute);
enum class LanesModel { kFollowTheLeader, kCompliant };
// kAuto's choice for the follow-the-leader model: the lane kernel where the strand fits the subgroup, no strand is
// pinned at its tip, and the groom has at most about 2,560 strands of 32 lanes (fused.cpp: the measured crossover).
bool ftl_lanes_by_default(uint32_t guide_count, uint32_t vertices_per_strand, bool fits_subgroup, bool pinned_tips);
PassUse frame_lanes_pass_use(const SceneTerms& terms, bool subgroup, LanesModel model);
bool is_frame_lanes(const PassInfo* info);
// Its workgroup size (WORKGROUP_SIZE): shared, the power of two >= N, at least 32; subgroup, whole subgroups, at
// least 64 invocations. And its workgroups for G guides.
uint32_t frame_lanes_workgroup(const PassInfo* info, uint32_t vertices_per_strand, uint32_t subgroup_size);
uint32_t frame_lanes_groups(const PassInfo* info, uint32_t guide_count, uint32_t vertices_per_strand,
                            uint32_t subgroup_size);

}  // namespace tressvk::sim
