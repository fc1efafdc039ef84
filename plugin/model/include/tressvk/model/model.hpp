// The model's rest data, derived once per asset in double precision, and its float32 GPU form. Both the CPU
// reference and the GPU passes use exactly this data, so they simulate the same model.
//
// From the asset the model takes the positions and inverse masses, the root frame (frame[0]), the groups, bone
// weights and follow offsets as they are. The rest lengths it computes with the baker's formula from the same
// float32 positions, in double for the reference (the float32 the GPU gets equals the asset's rest_lengths bit for
// bit). The frames along the strand and the rest edges are its own (below), so the asset's frame[v > 0] and
// rest_edge_local are not read at runtime; tests/plugin/reference/test_model_rest.cpp checks all of this.
//
// Beyond what the asset stores, the model decides per vertex whether the local-shape frame turns onto the edge
// arriving at v (an edge much shorter than the one leaving v has an unreliable direction in float32, so the frame
// is carried over it), and re-expresses each rest edge in the frame so defined; and it pins whole strands that
// are tiny compared with the groom (kRigidStrandRel).
#pragma once

#include <cstdint>
#include <vector>

#include <tressvk/asset.hpp>

#include "tressvk/model/gpu_layout.hpp"
#include "tressvk/model/math.hpp"

namespace tressvk::model {

// An edge arriving at v drives the frame only if it is at least this fraction of the edge leaving v (so a frame
// direction error from float rounding, delta/|e_in|, moves the next target by at most delta/kFrameEdgeRatio),
// and at least kFrameEdgeMinRel of the strand's mean segment.
inline constexpr double kFrameEdgeRatio = 0.2;
inline constexpr double kFrameEdgeMinRel = 1e-3;
// A strand with a segment shorter than kRespaceBelowRel of its mean segment has its free vertices respaced evenly along
// it on load (build_model_rest): float32 cannot hold the direction of a sub-micrometre segment at real scale, and the
// compliant model's length solve amplified that rounding 1e4-fold (hard case 8, docs/accuracy.md).
inline constexpr double kRespaceBelowRel = 1e-2;
// The share of the follow-the-leader move of a child that its parent receives back as velocity (DFTL, Mueller
// et al. 2012, who recommend 0.9..1). GLSL twin: kFtlVelocityCorrection in common.glsl.
inline constexpr double kFtlVelocityCorrection = 0.9;
// The length solve's smallest pivot, relative to its row's diagonal: a row whose pivot falls below it (a taut strand
// pinned at both ends, whose constraints are dependent) takes this instead, so the solve stays bounded. GLSL twin:
// kSolvePivotMin in common.glsl.
inline constexpr double kSolvePivotMin = 1e-6;
// Capsule contacts deeper than this fraction of the radius lose all their inward velocity; shallower ones in
// proportion (a continuous response). GLSL twin: kContactBand.
inline constexpr double kContactBand = 0.02;
// An edge shorter than this fraction of its rest length gets its direction blended with its previous one (length
// constraints) or the frame's axis (local shape) by the missing length. GLSL twin: kCollapse.
inline constexpr double kCollapse = 1.0;
// Strands shorter than this fraction of the groom's median strand length are carried rigidly (all pinned): short
// hair barely bends under its own weight (the gravito-bending length of a human hair is about 4.5 cm), and such a
// strand resolved into N vertices has sub-millimetre segments whose dynamics mostly amplify rounding.
inline constexpr double kRigidStrandRel = 0.45;
// GLSL twin: kDirectionEps in common.glsl.
inline constexpr double kDirectionEps = 1e-4;

struct ModelRest {
  uint32_t guide_count = 0;        // G
  uint32_t vertices_per_strand = 0;// N
  uint32_t follow_per_guide = 0;   // K
  double asset_tip_separation = 0;
  std::array<double, 3> asset_origin{};
  // The bones the strands read, compacted: bone_count of them (0 = rigid only), bone_source[i] the asset bone that
  // compact bone i is, in the asset's order; bone_index names compact bones. A host frame still carries every one of
  // the asset's asset_bone_count bones; the planner picks the compact ones (FramePlanner::set_bone_source), so every
  // per-bone cost of a frame (planning in double, the upload, the ring) scales with the bones read: Ratboy's mohawk
  // reads 21 of its 105.
  uint32_t bone_count = 0;
  uint32_t asset_bone_count = 0;   // the asset's bones (0 when it has no bone weights)
  std::vector<uint32_t> bone_source;

  // Per guide vertex (G*N).
  std::vector<Vec3> rest_pos;      // asset space relative to the asset origin (the float values, widened)
  std::vector<double> inv_mass;    // 0 = pinned
  std::vector<double> rest_length; // edge v -> v+1 (0 at the tip)
  std::vector<double> arc_fraction;// rest arc length from the root / strand length
  std::vector<uint8_t> frame_turns;// 1 = the frame turns onto the edge arriving at v
  std::vector<Vec3> rest_edge_local;
  // Per guide.
  std::vector<Quat> root_frame;
  std::vector<double> strand_length;
  std::vector<uint32_t> group;
  // Compact bone indices (a zero weight's index is the strand's first weighted bone, so that index 0 always names
  // a bone the strand reads: the blend's quaternion hemisphere is the first entry's).
  std::vector<std::array<uint32_t, 4>> bone_index;
  std::vector<std::array<double, 4>> bone_weight;
  // Per follow (G*K).
  std::vector<Vec3> follow_offset;
  std::vector<double> follow_length;  // rest arc length of the follow (asset tip separation), for health metrics
  uint32_t group_count = 1;
  double median_length = 0;    // the median of strand_length
  uint32_t rigid_strands = 0;  // strands the default rigid_below (kRigidStrandRel x median) carries rigidly
  uint32_t pinned_tip_strands = 0;  // strands with a pinned tip and a free vertex (TressFX bothEndsImmovable)
  uint32_t respaced_strands = 0;    // strands whose free vertices were respaced on load (kRespaceBelowRel)
};

// Throws std::invalid_argument naming the field when the asset is inconsistent.
ModelRest build_model_rest(const asset::HairAsset& asset);

// The static buffers (bindings 4..11) exactly as the GPU reads them. Buffers that would be empty (no follows, no
// bones) hold one zero element, since Vulkan buffers cannot be empty.
struct GpuStatic {
  // Per-vertex data in the blocked layout (sim::vertex_index), padded to whole strand blocks.
  std::vector<sim::Vec4> rest_positions;    // binding 4: a guide's root, then its vertices' offsets from the root
  std::vector<sim::Vec4> rest_info;         // binding 5
  std::vector<sim::Vec4> rest_edge_local;   // binding 6
  std::vector<sim::Vec4> root_frames;       // binding 7
  std::vector<sim::Vec4> follow_offsets;    // binding 8
  std::vector<sim::UVec4> guide_info;       // binding 9
  std::vector<sim::UVec4> bone_indices;     // binding 10
  std::vector<sim::Vec4> bone_weights;      // binding 11
};
GpuStatic build_gpu_static(const ModelRest& rest);

// Median of the guides' rest lengths: the normalisation of every error metric.
double median_strand_length(const ModelRest& rest);

// TvkSimParams::rigid_below's default (a negative value): kRigidStrandRel x the asset's median strand length (m).
inline double default_rigid_below(double median_length) { return kRigidStrandRel * median_length; }
// Whether a strand of rest arc length `strand_length` is carried rigidly under threshold `rigid_below` (m), compared
// in float32 as the GPU compares them (GroupParams::rigid_below against the strand length it stores).
inline bool rigid_by_rule(double strand_length, double rigid_below) {
  return static_cast<float>(strand_length) < static_cast<float>(rigid_below);
}

}  // namespace tressvk::model
