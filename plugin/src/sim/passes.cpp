#include "sim/passes.hpp"

#include <array>
#include <cmath>

#include "tressvk_sim_spirv.h"

namespace tressvk::sim {
namespace {

constexpr uint32_t bits(std::initializer_list<uint32_t> list) {
  uint32_t out = 0;
  for (uint32_t b : list) out |= binding_bit(b);
  return out;
}

constexpr uint32_t kSkinReads = bits({kBindingBoneIndices, kBindingBoneWeights, kBindingSkin});

const std::array<PassInfo, 5> kPasses = {{
    {PassId::kIntegrate, "integrate", k_spv_integrate_comp, sizeof(k_spv_integrate_comp),
     Granularity::kGuideVertex, Frequency::kPerSubstep,
     bits({kBindingPositions, kBindingPrevPositions, kBindingPrevPrevPositions, kBindingRestPositions,
           kBindingRestInfo, kBindingGuideInfo, kBindingGroups, kBindingSteps}) | kSkinReads,
     bits({kBindingPositions, kBindingPrevPositions, kBindingPrevPrevPositions, kBindingAnchors}),
     kFeatureGlobalShape | kFeatureSkinning, false},
    {PassId::kVsp, "vsp", k_spv_vsp_comp, sizeof(k_spv_vsp_comp), Granularity::kGuideVertex,
     Frequency::kPerSubstep,
     bits({kBindingPositions, kBindingPrevPositions, kBindingPrevPrevPositions, kBindingGuideInfo,
           kBindingGroups}) | kSkinReads,
     bits({kBindingPositions}), kFeatureSkinning, false},
    {PassId::kLocalShape, "local_shape", k_spv_local_shape_comp, sizeof(k_spv_local_shape_comp),
     Granularity::kGuide, Frequency::kPerSubstep,
     bits({kBindingPositions, kBindingRestInfo, kBindingRestEdgeLocal, kBindingRootFrames, kBindingGuideInfo,
           kBindingGroups}) | kSkinReads,
     bits({kBindingPositions}), kFeatureSkinning, false},
    {PassId::kLength, "length", k_spv_length_comp, sizeof(k_spv_length_comp), Granularity::kGuide,
     Frequency::kPerSubstep,
     bits({kBindingPositions, kBindingPrevPositions, kBindingRestPositions, kBindingRestInfo,
           kBindingRootFrames, kBindingGuideInfo, kBindingGroups, kBindingSteps, kBindingCounters,
           kBindingAnchors}) | kSkinReads,
     bits({kBindingPositions, kBindingPrevPositions, kBindingPrevPrevPositions, kBindingTangents,
           kBindingCounters}),
     kFeatureWind | kFeatureCollision | kFeatureMaxSpeed | kFeatureSkinning | kFeaturePinnedTips, true},
    {PassId::kFollow, "follow", k_spv_follow_comp, sizeof(k_spv_follow_comp), Granularity::kFollowVertex,
     Frequency::kPerFrame,
     bits({kBindingPositions, kBindingTangents, kBindingRestInfo, kBindingRootFrames, kBindingFollowOffsets,
           kBindingGuideInfo, kBindingGroups}) | kSkinReads,
     bits({kBindingPositions, kBindingTangents}), kFeatureSkinning, false},
}};

}  // namespace

std::span<const PassInfo> pass_table() { return kPasses; }

const PassInfo& pass_info(PassId id) { return kPasses[static_cast<size_t>(id)]; }

SceneTerms scene_terms(std::span<const TvkSimParams> groups, const TvkSimFrame& frame, uint32_t follow_per_guide,
                       bool pinned_tips) {
  SceneTerms t;
  if (pinned_tips) t.features |= kFeaturePinnedTips;
  for (const TvkSimParams& g : groups) {
    if (g.vsp_coefficient > 0.0f) t.vsp = true;
    if (g.local_stiffness > 0.0f && g.local_iterations > 0) t.local_shape = true;
    if (g.global_stiffness > 0.0f && g.global_range > 0.0f) t.features |= kFeatureGlobalShape;
    if (g.max_speed > 0.0f) t.features |= kFeatureMaxSpeed;
  }
  t.follow = follow_per_guide > 0;
  const TvkWind& w = frame.wind;
  if (w.strength != 0.0f && (w.direction[0] != 0.0f || w.direction[1] != 0.0f || w.direction[2] != 0.0f)) {
    t.features |= kFeatureWind;
  }
  if (frame.capsule_count > 0) {
    t.features |= kFeatureCollision;
    t.capsule_count = frame.capsule_count < kMaxCapsules ? frame.capsule_count : kMaxCapsules;
  }
  if (frame.bones != nullptr && frame.bone_count > 0) t.features |= kFeatureSkinning;
  return t;
}

std::vector<PassUse> passes_for(const SceneTerms& terms) {
  std::vector<PassUse> out;
  for (const PassInfo& p : kPasses) {
    if (p.id == PassId::kVsp && !terms.vsp) continue;
    if (p.id == PassId::kLocalShape && !terms.local_shape) continue;
    if (p.id == PassId::kFollow && !terms.follow) continue;
    PassUse use{&p, p.base_name, terms.features & p.features_used, p.uses_capsule_count ? terms.capsule_count : 0};
    // Names show the compiled terms a reader cares about (skinning is a detail of every pass, not shown).
    if (use.features & kFeatureGlobalShape) use.name += "+global";
    if (use.features & kFeatureWind) use.name += "+wind";
    if (use.features & kFeatureCollision) use.name += "+collision";
    if (use.features & kFeatureMaxSpeed) use.name += "+clamp";
    if (use.features & kFeaturePinnedTips) use.name += "+pinned-tips";
    out.push_back(std::move(use));
  }
  return out;
}

uint32_t dispatch_groups(Granularity granularity, uint32_t guide_count, uint32_t vertices_per_strand,
                         uint32_t follow_per_guide, uint32_t workgroup_size) {
  uint64_t threads = 0;
  switch (granularity) {
    // Per-vertex passes cover whole strand blocks (thread i = element i of the blocked layout).
    case Granularity::kGuideVertex: threads = padded_strands(guide_count) * vertices_per_strand; break;
    case Granularity::kGuide: threads = guide_count; break;
    case Granularity::kFollowVertex:
      threads = padded_strands(uint64_t{guide_count} * follow_per_guide) * vertices_per_strand;
      break;
  }
  if (workgroup_size == 0) return 0;
  return static_cast<uint32_t>((threads + workgroup_size - 1) / workgroup_size);
}

}  // namespace tressvk::sim
