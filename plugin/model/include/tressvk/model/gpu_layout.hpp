// Host mirror of shaders/sim/layout.glsl: binding numbers, specialization constant ids, feature bits and the
// std430 structs, with static_asserts on every size and offset. Change both files together. The numbers are defined
// once in gpu_layout.h, which the shaders include too; the enums below are asserted equal to it (end of file).
//
// Header-only and Vulkan-free so that the CPU reference (plugin/reference) can fill these structs too
// (model::to_gpu), which keeps one conversion from the frame planner's double-precision substeps to what the
// shaders read.
#pragma once

#include "tressvk/model/gpu_layout.h"
#include "tressvk/sim_types.h"

#include <array>
#include <cstddef>
#include <cstdint>

namespace tressvk::sim {

// ---- descriptor set 0 bindings (all storage buffers) ----
enum Binding : uint32_t {
  // Per-vertex buffers use the blocked layout below; sizes are padded_strands(...) * N.
  kBindingPositions = 0,        // vec4 x padded(G*(K+1))*N, read-write (offsets from the strand's anchor)
  kBindingPrevPositions = 1,    // vec4 x padded(G)*N, read-write
  kBindingPrevPrevPositions = 2,// vec4 x padded(G)*N, read-write
  kBindingTangents = 3,         // vec4 x padded(G*(K+1))*N, written
  kBindingRestPositions = 4,    // vec4 x padded(G)*N, static (v = 0: the root; v > 0: offset from the root)
  kBindingRestInfo = 5,         // vec4 x padded(G)*N, static
  kBindingRestEdgeLocal = 6,    // vec4 x padded(G)*N, static
  kBindingRootFrames = 7,       // vec4 x G, static
  kBindingFollowOffsets = 8,    // vec4 x G*K, static (a 16-byte dummy when K = 0)
  kBindingGuideInfo = 9,        // uvec4 x G, static
  kBindingBoneIndices = 10,     // uvec4 x G, static (a 16-byte dummy without bones)
  kBindingBoneWeights = 11,     // vec4 x G, static (a 16-byte dummy without bones)
  kBindingSkin = 12,            // vec4 x kSkinVec4PerBone per (substep, bone), per frame
  kBindingGroups = 13,          // GroupParams x groups, per frame
  kBindingSteps = 14,           // StepParams x substeps, per frame
  kBindingCounters = 15,        // uint per frame slot (resets, kCounterAwakeBit), host-visible, read-write
  kBindingAnchors = 16,         // vec4 x G, written by integrate: each guide's anchor (its skinned rest root)
};
inline constexpr uint32_t kBindingCount = 17;
inline constexpr uint32_t kCounterAwakeBit = TVK_COUNTER_AWAKE_BIT;

// ---- specialization constants ----
enum SpecConstant : uint32_t {
  kSpecWorkgroupSize = 0,
  kSpecVerticesPerStrand = 1,  // N
  kSpecFollowPerGuide = 2,     // K
  kSpecFeatures = 3,           // Feature bits
  kSpecCapsuleCount = 4,
};

enum Feature : uint32_t {
  kFeatureGlobalShape = 1u,
  kFeatureWind = 2u,
  kFeatureCollision = 4u,
  kFeatureSkinning = 8u,
  kFeatureMaxSpeed = 16u,
  kFeaturePinnedTips = 32u,  // length: some strand is pinned at its tip too (the tridiagonal length solve)
  kFeatureVsp = 64u,         // fused frame kernel only (sim/fused.hpp): run VSP
  kFeatureLocalShape = 128u, // fused frame kernel only: run local shape constraints
  kFeatureConservative = 256u,  // lane kernel only: the conservative local shape
  kFeatureRefine = 512u,        // with kFeatureConservative: its shape solve refined once (sim/fused.hpp)
  kFeatureRefineThrice = 1024u,  // with kFeatureRefine: refined three times (sim/fused.hpp)
};

// Vertex layout of every per-vertex buffer (positions, tangents, the histories, the static rest data): strands in
// blocks of kStrandBlock, vertex-major within a block, so that the threads of a subgroup walking their strands read
// consecutive addresses. Vertex v of strand s is at strand_base(s, N) + v * kStrandBlock; buffers hold whole blocks.
inline constexpr uint32_t kStrandBlock = TVK_BLOCK;
constexpr uint64_t padded_strands(uint64_t strands) {
  return (strands + kStrandBlock - 1) / kStrandBlock * kStrandBlock;
}
constexpr uint64_t vertex_index(uint64_t strand, uint64_t v, uint64_t n) {
  return strand / kStrandBlock * (uint64_t{kStrandBlock} * n) + v * kStrandBlock + strand % kStrandBlock;
}

inline constexpr uint32_t kStepReset = 1u;       // StepParams::flags[0] bits
inline constexpr uint32_t kStepMoveState = 2u;
inline constexpr uint32_t kMaxCapsules = 8;
inline constexpr uint32_t kSkinVec4PerBone = 9;  // 3 affine rows, rotation, rotation since the last step, the
                                                  // previous step's rotation since the one before, 3 rows of the
                                                  // map's change since the last step (the anchors' move)

struct GroupParams {
  float velocity_keep;
  float global_stiffness;
  float global_range;
  float local_stiffness;
  uint32_t local_iterations;
  uint32_t length_iterations;
  float vsp_coefficient;
  float vsp_threshold;
  float max_step;
  float tip_separation;
  float reserved0;
  float reserved1;
  float rigid_below;  // m: strands shorter than this are pinned whole (0 = none)
  float reserved2;
  float reserved3;
  float reserved4;
};
static_assert(sizeof(GroupParams) == 64);
static_assert(offsetof(GroupParams, rigid_below) == 48);
static_assert(offsetof(GroupParams, local_iterations) == 16);
static_assert(offsetof(GroupParams, vsp_coefficient) == 24);
static_assert(offsetof(GroupParams, max_step) == 32);
static_assert(offsetof(GroupParams, tip_separation) == 36);

struct StepParams {
  std::array<float, 4> gravity;        // xyz g*h^2, w h
  std::array<float, 4> origin_shift;   // xyz
  std::array<float, 4> teleport;       // quaternion (x,y,z,w)
  std::array<uint32_t, 4> flags;       // [0] kStep* bits, [1] substep index
  std::array<std::array<float, 4>, 4> wind;                  // xyz acceleration*h^2
  std::array<std::array<float, 4>, 2 * kMaxCapsules> capsule;  // [2c] (p0, r0), [2c+1] (p1, r1)
  std::array<std::array<float, 4>, 2 * kMaxCapsules> capsule_move;  // [2c] p0's move this step, [2c+1] p1's
};
static_assert(sizeof(StepParams) == 640);
static_assert(offsetof(StepParams, origin_shift) == 16);
static_assert(offsetof(StepParams, teleport) == 32);
static_assert(offsetof(StepParams, flags) == 48);
static_assert(offsetof(StepParams, wind) == 64);
static_assert(offsetof(StepParams, capsule) == 128);
static_assert(offsetof(StepParams, capsule_move) == 384);

struct PushConstants {
  uint32_t guide_count;
  uint32_t step_index;
  uint32_t skin_base;      // index of a vec4 in the Skin buffer
  uint32_t group_base;
  uint32_t counter_index;  // the frame slot's word in the counters buffer (layout.glsl: resets, awake bit)
  uint32_t step_count = 0;   // fused frame kernel: substeps to run
  uint32_t skin_stride = 0;  // fused frame kernel: vec4 of skinning data per substep
  float rest_move = 0;       // fused frame kernels: m per step, > 0 in a still frame (layout.glsl, sleeping strands)
  uint32_t follow_strands = 0;  // rendered strands whose follow hairs are written (layout.glsl, follow_drawn)
};
static_assert(sizeof(PushConstants) == 36);
static_assert(sizeof(PushConstants) <= 128);

using Vec4 = std::array<float, 4>;
using UVec4 = std::array<uint32_t, 4>;
static_assert(sizeof(Vec4) == 16 && sizeof(UVec4) == 16);

// One layout: the enums and constants above are gpu_layout.h's numbers, and the public limits are the same.
static_assert(kBindingPositions == TVK_BINDING_POSITIONS && kBindingPrevPositions == TVK_BINDING_PREV_POSITIONS &&
              kBindingPrevPrevPositions == TVK_BINDING_PREV_PREV_POSITIONS && kBindingTangents == TVK_BINDING_TANGENTS &&
              kBindingRestPositions == TVK_BINDING_REST_POSITIONS && kBindingRestInfo == TVK_BINDING_REST_INFO &&
              kBindingRestEdgeLocal == TVK_BINDING_REST_EDGE_LOCAL && kBindingRootFrames == TVK_BINDING_ROOT_FRAMES &&
              kBindingFollowOffsets == TVK_BINDING_FOLLOW_OFFSETS && kBindingGuideInfo == TVK_BINDING_GUIDE_INFO &&
              kBindingBoneIndices == TVK_BINDING_BONE_INDICES && kBindingBoneWeights == TVK_BINDING_BONE_WEIGHTS &&
              kBindingSkin == TVK_BINDING_SKIN && kBindingGroups == TVK_BINDING_GROUPS &&
              kBindingSteps == TVK_BINDING_STEPS && kBindingCounters == TVK_BINDING_COUNTERS &&
              kBindingAnchors == TVK_BINDING_ANCHORS && kBindingCount == TVK_BINDING_COUNT);
static_assert(kSpecWorkgroupSize == TVK_SPEC_WORKGROUP_SIZE && kSpecVerticesPerStrand == TVK_SPEC_VERTICES_PER_STRAND &&
              kSpecFollowPerGuide == TVK_SPEC_FOLLOW_PER_GUIDE && kSpecFeatures == TVK_SPEC_FEATURES &&
              kSpecCapsuleCount == TVK_SPEC_CAPSULE_COUNT);
static_assert(kFeatureGlobalShape == TVK_FEATURE_GLOBAL_SHAPE && kFeatureWind == TVK_FEATURE_WIND &&
              kFeatureCollision == TVK_FEATURE_COLLISION && kFeatureSkinning == TVK_FEATURE_SKINNING &&
              kFeatureMaxSpeed == TVK_FEATURE_MAX_SPEED && kFeaturePinnedTips == TVK_FEATURE_PINNED_TIPS &&
              kFeatureVsp == TVK_FEATURE_VSP && kFeatureLocalShape == TVK_FEATURE_LOCAL_SHAPE &&
              kFeatureConservative == TVK_FEATURE_CONSERVATIVE && kFeatureRefine == TVK_FEATURE_REFINE &&
              kFeatureRefineThrice == TVK_FEATURE_REFINE_THRICE);
static_assert(vertex_index(37, 5, 9) == TVK_VERTEX_INDEX(37u, 5u, 9u));
static_assert(kStepReset == TVK_STEP_RESET && kStepMoveState == TVK_STEP_MOVE_STATE &&
              kSkinVec4PerBone == TVK_SKIN_VEC4 && kMaxCapsules == TVK_STEP_MAX_CAPSULES &&
              kMaxCapsules == TVK_MAX_CAPSULES);
static_assert(TVK_QUIET_FRAMES == TVK_ASLEEP_QUIET_FRAMES);

}  // namespace tressvk::sim
