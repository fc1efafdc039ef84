#include "sim/fused.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "tressvk_sim_spirv.h"

namespace tressvk::sim {
namespace {

constexpr uint32_t all_bindings() { return (1u << kBindingCount) - 1u; }

// Reads and writes are the union of the five passes' (the hazard tracker needs no more precision for one dispatch).
constexpr uint32_t kFrameWrites = binding_bit(kBindingPositions) | binding_bit(kBindingPrevPositions) |
                                  binding_bit(kBindingPrevPrevPositions) | binding_bit(kBindingTangents) |
                                  binding_bit(kBindingCounters) | binding_bit(kBindingAnchors);
constexpr uint32_t kFrameFeatures = kFeatureGlobalShape | kFeatureWind | kFeatureCollision | kFeatureSkinning |
                                    kFeatureMaxSpeed | kFeaturePinnedTips | kFeatureVsp | kFeatureLocalShape;

const PassInfo kFramePrivate = {PassId::kFrame, "frame", k_spv_frame_comp, sizeof(k_spv_frame_comp),
                                Granularity::kGuide, Frequency::kPerFrame, all_bindings(), kFrameWrites,
                                kFrameFeatures, true};
const PassInfo kFrameShared = {PassId::kFrame, "frame", k_spv_frame_shared_comp, sizeof(k_spv_frame_shared_comp),
                               Granularity::kGuide, Frequency::kPerFrame, all_bindings(), kFrameWrites,
                               kFrameFeatures, true};
const PassInfo kFrameLanes = {PassId::kFrame, "frame", k_spv_frame_lanes_comp, sizeof(k_spv_frame_lanes_comp),
                              Granularity::kGuide, Frequency::kPerFrame, all_bindings(), kFrameWrites,
                              kFrameFeatures, true};
const PassInfo kFrameLanesSubgroup = {PassId::kFrame, "frame", k_spv_frame_lanes_subgroup_comp,
                                      sizeof(k_spv_frame_lanes_subgroup_comp), Granularity::kGuide,
                                      Frequency::kPerFrame, all_bindings(), kFrameWrites, kFrameFeatures, true};
const PassInfo kFrameLanesFtl = {PassId::kFrame, "frame", k_spv_frame_lanes_ftl_comp,
                                 sizeof(k_spv_frame_lanes_ftl_comp), Granularity::kGuide, Frequency::kPerFrame,
                                 all_bindings(), kFrameWrites, kFrameFeatures, true};
const PassInfo kFrameLanesFtlSubgroup = {PassId::kFrame, "frame", k_spv_frame_lanes_ftl_subgroup_comp,
                                         sizeof(k_spv_frame_lanes_ftl_subgroup_comp), Granularity::kGuide,
                                         Frequency::kPerFrame, all_bindings(), kFrameWrites, kFrameFeatures, true};
constexpr uint32_t kLanesVariantBit = 1u << 14;
// Keeps the follow-the-leader lane kernels' pipelines apart from the compliant model's (FEATURES ignores it).
constexpr uint32_t kLanesFtlBit = 1u << 13;
// The follow-the-leader lane kernel runs its serial walks on every lane of the strand (one or two lanes do useful
// work), so it issues about LANES times the walks' instructions of the one-thread kernel: it wins while the GPU is
// short of strands to overlap (latency-bound), and loses once the lanes fill it. Measured on an NVIDIA H100, shake,
// 32 vertices: 1,024 guides 43 / 125 us at 60 / 240 Hz against 74 / 205; 2,221 (Ratboy) 60 / 192 against 80 / 214;
// 4,096 89 / 302 against 78 / 208 (docs/simulation.md). The crossover at 240 Hz is near 2,500 strands of 32 lanes.
constexpr uint64_t kFtlLanesDefaultMaxInvocations = 2560u * 32u;
// Workgroup size of the subgroup variant: whole subgroups, at least this many invocations.
constexpr uint32_t kLanesSubgroupWorkgroup = 64;

uint32_t lanes_for(uint32_t vertices_per_strand, uint32_t at_least) {
  uint32_t lanes = at_least;
  while (lanes < vertices_per_strand) lanes *= 2;
  return lanes;
}
// Not a shader feature: keeps the two variants' pipelines apart in the context's pipeline cache (FEATURES ignores it).
constexpr uint32_t kSharedVariantBit = 1u << 15;  // below bit 16: the cache key puts capsules at bit 48

}  // namespace

SimPath sim_path_from_environment() {
  static const SimPath path = [] {
    const char* v = std::getenv("TRESSVK_SIM_PATH");
    if (v && std::strcmp(v, "passes") == 0) return SimPath::kPasses;
    if (v && std::strcmp(v, "fused-shared") == 0) return SimPath::kFusedShared;
    if (v && std::strcmp(v, "fused") == 0) return SimPath::kFused;
    if (v && std::strcmp(v, "lanes") == 0) return SimPath::kLanes;
    return SimPath::kAuto;
  }();
  return path;
}

uint32_t frame_shared_bytes(uint32_t vertices_per_strand, bool /*vsp*/) {
  // Positions and their history; VSP's second history lives in registers (frame_shared.comp).
  return kStrandBlock * vertices_per_strand * 16u * 2u;
}

PassUse frame_pass_use(const SceneTerms& terms, bool shared) {
  PassUse use{shared ? &kFrameShared : &kFramePrivate, "frame", terms.features, terms.capsule_count};
  if (terms.vsp) use.features |= kFeatureVsp;
  if (terms.local_shape) use.features |= kFeatureLocalShape;
  if (shared) use.features |= kSharedVariantBit;
  if (shared) use.name += "(shared)";
  if (use.features & kFeatureVsp) use.name += "+vsp";
  if (use.features & kFeatureLocalShape) use.name += "+local_shape";
  if (use.features & kFeatureGlobalShape) use.name += "+global";
  if (use.features & kFeatureWind) use.name += "+wind";
  if (use.features & kFeatureCollision) use.name += "+collision";
  if (use.features & kFeatureMaxSpeed) use.name += "+clamp";
  if (use.features & kFeaturePinnedTips) use.name += "+pinned-tips";
  if (terms.follow) use.name += "+follow";
  return use;
}

uint32_t frame_dispatch_groups(uint32_t guide_count) { return (guide_count + kStrandBlock - 1) / kStrandBlock; }

LanesBackend lanes_backend_from_environment() {
  static const LanesBackend backend = [] {
    const char* v = std::getenv("TRESSVK_SIM_LANES");
    if (v && std::strcmp(v, "shared") == 0) return LanesBackend::kShared;
    return LanesBackend::kAuto;
  }();
  return backend;
}

bool lanes_fit_subgroup(uint32_t vertices_per_strand, uint32_t subgroup_size, bool shuffle_compute) {
  return shuffle_compute && subgroup_size >= 4 && (subgroup_size & (subgroup_size - 1)) == 0 &&
         lanes_for(vertices_per_strand, 1) <= subgroup_size;
}

bool ftl_lanes_by_default(uint32_t guide_count, uint32_t vertices_per_strand, bool fits_subgroup, bool pinned_tips) {
  return fits_subgroup && !pinned_tips &&
         uint64_t{guide_count} * lanes_for(vertices_per_strand, 1) <= kFtlLanesDefaultMaxInvocations;
}

PassUse frame_lanes_pass_use(const SceneTerms& terms, bool subgroup, LanesModel model) {
  PassUse use = frame_pass_use(terms, false);
  const bool ftl = model == LanesModel::kFollowTheLeader;
  use.info = ftl ? (subgroup ? &kFrameLanesFtlSubgroup : &kFrameLanesFtl)
                 : (subgroup ? &kFrameLanesSubgroup : &kFrameLanes);
  use.features |= kLanesVariantBit;
  if (ftl) use.features |= kLanesFtlBit;
  if (subgroup) use.features |= kSharedVariantBit;  // keeps the two lane variants' pipelines apart
  use.name = (subgroup ? "frame(lanes,subgroup)" : "frame(lanes)") + use.name.substr(5);
  return use;
}

bool is_frame_lanes(const PassInfo* info) {
  return info == &kFrameLanes || info == &kFrameLanesSubgroup || info == &kFrameLanesFtl ||
         info == &kFrameLanesFtlSubgroup;
}

namespace {
bool is_subgroup_lanes(const PassInfo* info) { return info == &kFrameLanesSubgroup || info == &kFrameLanesFtlSubgroup; }
}  // namespace

uint32_t frame_lanes_workgroup(const PassInfo* info, uint32_t vertices_per_strand, uint32_t subgroup_size) {
  if (is_subgroup_lanes(info)) return std::max(subgroup_size, kLanesSubgroupWorkgroup);
  return lanes_for(vertices_per_strand, 32);
}

uint32_t frame_lanes_groups(const PassInfo* info, uint32_t guide_count, uint32_t vertices_per_strand,
                            uint32_t subgroup_size) {
  if (!is_subgroup_lanes(info)) return guide_count;
  const uint32_t per_group = frame_lanes_workgroup(info, vertices_per_strand, subgroup_size) /
                             lanes_for(vertices_per_strand, 1);
  return (guide_count + per_group - 1) / per_group;
}

}  // namespace tressvk::sim
