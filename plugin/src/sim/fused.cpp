#include "sim/fused.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "tressvk_sim_spirv.h"
#include <tressvk/model/planner.hpp>

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
// The same kernel for grooms with follow hairs (frame_follows.comp: each follow vertex written with its guide's); the
// one without keeps no follow code in its module, where the driver's register allocation would see it.
const PassInfo kFramePrivateFollows = {PassId::kFrame, "frame", k_spv_frame_follows_comp,
                                       sizeof(k_spv_frame_follows_comp), Granularity::kGuide, Frequency::kPerFrame,
                                       all_bindings(), kFrameWrites, kFrameFeatures, true};
const PassInfo kFrameShared = {PassId::kFrame, "frame", k_spv_frame_shared_comp, sizeof(k_spv_frame_shared_comp),
                               Granularity::kGuide, Frequency::kPerFrame, all_bindings(), kFrameWrites,
                               kFrameFeatures, true};
const PassInfo kFrameLanes = {PassId::kFrame, "frame", k_spv_frame_lanes_comp, sizeof(k_spv_frame_lanes_comp),
                              Granularity::kGuide, Frequency::kPerFrame, all_bindings(), kFrameWrites,
                              kFrameFeatures, true};
const PassInfo kFrameLanesSubgroup = {PassId::kFrame, "frame", k_spv_frame_lanes_subgroup_comp,
                                      sizeof(k_spv_frame_lanes_subgroup_comp), Granularity::kGuide,
                                      Frequency::kPerFrame, all_bindings(), kFrameWrites, kFrameFeatures, true};
// One SPIR-V, two run lengths (RUN, specialisation constant 5): the host tells them apart by the PassInfo.
const PassInfo kFrameRuns4 = {PassId::kFrame, "frame", k_spv_frame_runs_comp, sizeof(k_spv_frame_runs_comp),
                              Granularity::kGuide, Frequency::kPerFrame, all_bindings(), kFrameWrites, kFrameFeatures,
                              true};
const PassInfo kFrameRuns8 = kFrameRuns4;
constexpr uint32_t kLanesVariantBit = 1u << 14;
// The one-thread kernel in workgroups of 512 threads (FEATURES ignores it). A workgroup of 32 lets the driver give a
// thread up to 255 registers, and some variants take them: NVIDIA H100 (driver 580.159.04), 240 Hz, curly x 32, the
// kernel without VSP or without global shape 255 registers where the one with both has 128. Once a groom has enough
// strands to fill the GPU at 128 registers a thread, 255 halve the threads that run at once, and a scene that needs
// one pass less ran slower: 4 M guide vertices 1,775 us with every pass, 2,320 without VSP, 2,111 without global
// shape. A workgroup of 512 allows at most 128 (65,536 registers an SM): 1,786 / 1,761 / 1,681 us (bare, no VSP,
// global shape, clamp or local shape: 1,361 -> 1,197); 3 M 1,498 -> 1,523 with every pass, 1,745 -> 1,498 without
// VSP; 2 M 902 -> 901, 1,175 -> 891. With fewer strands, a workgroup of 512 leaves SMs without work: 1 M 612 -> 639
// us (without VSP 605 -> 635), a crowd of 64 Ratboys (each instance its own dispatch of 2,221 guides) 1,959 -> 1,978.
// So: 512 from 64 Ki guides (docs/simulation.md, "The one-thread kernel's workgroup").
constexpr uint32_t kFrameWideBit = 1u << 11;
// TRESSVK_SIM_FRAME_WG=32|512 forces the one-thread kernel's workgroup (for measurement); unset, the rule decides.
uint32_t frame_workgroup_from_environment() {
  static const uint32_t wg = [] {
    const char* v = std::getenv("TRESSVK_SIM_FRAME_WG");
    const uint32_t w = v ? static_cast<uint32_t>(std::strtoul(v, nullptr, 10)) : 0u;
    return w == kStrandBlock || w == kFrameWideWorkgroup ? w : 0u;
  }();
  return wg;
}
// The run kernel's pipelines, and its run of 4 (FEATURES ignores both).
constexpr uint32_t kRunsBit = 1u << 12;
constexpr uint32_t kRuns4Bit = 1u << 13;
// The run kernel issues each serial walk's instructions once per 32 / RL strands (RL lanes a strand) while the one-thread
// kernel issues them once per 32: it wins while the GPU is short of strands to overlap and its per-vertex phases
// matter, and loses once the strands fill it. Measured on an NVIDIA H100, curly x 32, shake, 240 Hz (60 Hz), us per
// frame, run of 4 / run of 8 / one-thread: 4,096 guides 128 / 131 / 206 (48 / 50 / 78); 8,192 242 / 154 / 243 (83 /
// 57 / 104); 16,384 409 / 319 / 400 (146 / 125 / 140); 32,768, run of 8 / one-thread, 608 / 606 (224 / 205)
// (docs/simulation.md). Bounds in guide vertices: a run of 4 up to 160 k, of 8 up to 768 k.
constexpr uint64_t kRuns4MaxGuideVertices = 160u * 1024u;
constexpr uint64_t kRuns8MaxGuideVertices = 768u * 1024u;
// A crowd (many instances in one tressvk_cmd_simulate) is not one big groom: each instance is its own dispatch, and
// once a call holds enough instances and guide vertices the one-thread kernel beats each instance's own run kernel,
// whatever the groom size chose alone. NVIDIA H100, shake, us per frame for the whole call, each instance's own runs
// against the one-thread kernel (docs/simulation.md, "A crowd"), Ratboy with its 2 follow hairs a guide:
//   240 Hz (4 steps): 2 / 4 / 6 / 8 / 16 / 64 Ratboys 161 / 280 / 395 / 460 / 847 / 3,213 against 228 / 288 / 313 /
//   361 / 539 / 1,955; 4 / 32 x curly 4,096 / 512 416 / 415 against 318 / 298; 8 x curly 512 (131 k) 134 against
//   204; 2 x curly 8,192 329 against 345.
//   120 Hz (2 steps): 4 / 6 / 8 / 64 Ratboys 165 / 229 / 261 / 1,701 against 171 / 193 / 220 / 1,180; 4 / 6 / 64 x
//   curly 2,221 148 / 207 / 1,661 against 154 / 175 / 1,025; 4 x curly 4,096 230 against 191; 32 x 512 229 / 182.
//   60 Hz (1 step): 4 / 6 / 8 / 64 Ratboys 112 / 150 / 165 / 974 against 118 / 132 / 151 / 789; 4 / 6 / 8 / 64 x
//   curly 2,221 89 / 122 / 149 / 909 against 102 / 118 / 132 / 660; 4 x curly 4,096 142 against 127; 32 x 512 139
//   against 123; 4 x 16,384 419 against 290.
// So, at any step rate: 4 or more instances with 400 k guide vertices between them. (Before the one-thread kernel
// wrote follow hairs with their guide, at 255 registers, it lost at 1 step and needed 8 instances at 2.) Both kernels
// give the same floats, so a frame may take either.
constexpr uint32_t kCrowdMinInstances = 4;
constexpr uint64_t kCrowdMinGuideVertices = 400u * 1024u;
// Workgroup size of the subgroup variant: whole subgroups, at least this many invocations.
constexpr uint32_t kLanesSubgroupWorkgroup = 64;
// With the conservative local shape: as many strands a workgroup as its shared memory holds, up to
// kConservativeSubgroupWorkgroup invocations; two of its subgroups solve their systems side by side, one from each
// end (lanes_compliant.glsl, conservative_solve). Its shared memory: per strand N nodes of 37 floats and the halves'
// exchange. NVIDIA H100, 240 Hz, before the quasi-definite form and the two-ended solve,
// strands of 32 vertices, the normal equations' 3x3 blocks (30 rows of 27 floats and a 3-vector a strand): 12 a
// workgroup of 384 (floats; 152 registers, 43 KB) Ratboy 301.8 us, curly 1 M 2,989; with mat3 storage 8 a workgroup
// of 256 (170 registers, 38 KB) 387.4 / 3,954, 4 of 128 383.9 / 4,198, 2 of 64 362.1 / 4,397: the solves are
// serial, so the more of them side by side in a subgroup, the better at 1 M.
constexpr uint32_t kConservativeSubgroupWorkgroup = 384;
constexpr uint32_t kConservativeNodeBytes = 37 * 4;
// frame_lanes.glsl, kSlotFloats: a strand's exchange floats (33), and one more to make its floats odd.
constexpr uint32_t kConservativeStrandPadBytes = 34 * 4;
constexpr uint32_t kConservativeFixedBytes = 64;  // the workgroup's iteration count and what a driver adds

uint32_t lanes_for(uint32_t vertices_per_strand, uint32_t at_least) {
  uint32_t lanes = at_least;
  while (lanes < vertices_per_strand) lanes *= 2;
  return lanes;
}
// Invocations of a strand in runs of run_length vertices.
uint32_t run_lanes(uint32_t vertices_per_strand, uint32_t run_length) {
  return lanes_for((vertices_per_strand + run_length - 1) / run_length, 1);
}
// A strand of `lanes` invocations fits the subgroup, and compute shaders may shuffle and vote.
bool strand_fits_subgroup(uint32_t lanes, uint32_t subgroup_size, bool shuffle_compute) {
  return shuffle_compute && subgroup_size >= 4 && (subgroup_size & (subgroup_size - 1)) == 0 && lanes <= subgroup_size;
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
    if (v && std::strcmp(v, "runs") == 0) return SimPath::kRuns;
    return SimPath::kAuto;
  }();
  return path;
}

uint32_t frame_shared_bytes(uint32_t vertices_per_strand, bool /*vsp*/) {
  // Positions and their history; VSP's second history lives in registers (frame_shared.comp).
  return kStrandBlock * vertices_per_strand * 16u * 2u;
}

PassUse frame_pass_use(const SceneTerms& terms, bool shared, uint32_t guide_count) {
  PassUse use{shared ? &kFrameShared : terms.follow ? &kFramePrivateFollows : &kFramePrivate, "frame", terms.features,
              terms.capsule_count};
  const uint32_t forced = frame_workgroup_from_environment();
  if (!shared && guide_count > 0 && (forced ? forced == kFrameWideWorkgroup : guide_count >= kFrameWideMinGuides)) {
    use.features |= kFrameWideBit;
    use.name = "frame(wide)";
  }
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

bool is_frame_private(const PassInfo* info) { return info == &kFramePrivate || info == &kFramePrivateFollows; }
uint32_t frame_private_workgroup(const PassUse& use) {
  return (use.features & kFrameWideBit) ? kFrameWideWorkgroup : kStrandBlock;
}
uint32_t frame_dispatch_groups(const PassUse& use, uint32_t guide_count) {
  const uint32_t wg = is_frame_private(use.info) ? frame_private_workgroup(use) : kStrandBlock;
  return (guide_count + wg - 1) / wg;
}

LanesBackend lanes_backend_from_environment() {
  static const LanesBackend backend = [] {
    const char* v = std::getenv("TRESSVK_SIM_LANES");
    if (v && std::strcmp(v, "shared") == 0) return LanesBackend::kShared;
    return LanesBackend::kAuto;
  }();
  return backend;
}

bool lanes_fit_subgroup(uint32_t vertices_per_strand, uint32_t subgroup_size, bool shuffle_compute) {
  return strand_fits_subgroup(lanes_for(vertices_per_strand, 1), subgroup_size, shuffle_compute);
}

uint32_t conservative_slots(uint32_t vertices_per_strand, uint32_t subgroup_size, uint32_t max_invocations,
                            uint32_t max_shared_bytes) {
  const uint32_t lanes = lanes_for(vertices_per_strand, 1);
  const uint32_t step = std::max(1u, subgroup_size / lanes);  // whole subgroups
  const uint64_t strand_bytes = uint64_t{vertices_per_strand} * kConservativeNodeBytes + kConservativeStrandPadBytes;
  const uint64_t by_shared = max_shared_bytes > kConservativeFixedBytes
                                 ? (max_shared_bytes - kConservativeFixedBytes) / strand_bytes : 0;
  const uint32_t by_size = std::min(kConservativeSubgroupWorkgroup, max_invocations) / lanes;
  const uint32_t slots = static_cast<uint32_t>(std::min<uint64_t>(by_shared, by_size)) / step * step;
  return slots;
}

PassUse frame_lanes_pass_use(const SceneTerms& terms, bool subgroup, bool conservative, uint32_t refinements) {
  const bool refine = conservative && refinements > 0;
  PassUse use = frame_pass_use(terms, false);
  use.info = subgroup ? &kFrameLanesSubgroup : &kFrameLanes;
  use.features |= kLanesVariantBit;
  if (subgroup) use.features |= kSharedVariantBit;  // keeps the two lane variants' pipelines apart
  if (conservative) use.features |= kFeatureConservative;
  if (refine) use.features |= kFeatureRefine;
  if (refine && refinements > 1) use.features |= kFeatureRefineThrice;
  const char* model = !conservative             ? ")"
                      : !refine                 ? ",conservative)"
                      : refinements > 1         ? ",conservative,refined thrice)"
                                                : ",conservative,refined)";
  use.name = std::string(subgroup ? "frame(lanes,subgroup" : "frame(lanes") + model + use.name.substr(5);
  return use;
}

uint32_t conservative_refinements_for(float step_rate) {
  static const int forced = [] {
    const char* v = std::getenv("TRESSVK_SIM_REFINE");
    if (v && (std::strcmp(v, "0") == 0 || std::strcmp(v, "1") == 0 || std::strcmp(v, "3") == 0)) return v[0] - '0';
    return -1;
  }();
  return forced >= 0 ? static_cast<uint32_t>(forced) : conservative_refinements(step_rate);
}

uint32_t run_length_from_environment() {
  static const uint32_t run = [] {
    const char* v = std::getenv("TRESSVK_SIM_RUN");
    if (v && std::strcmp(v, "4") == 0) return 4u;
    if (v && std::strcmp(v, "8") == 0) return 8u;
    return 0u;
  }();
  return run;
}

bool runs_fit_subgroup(uint32_t vertices_per_strand, uint32_t run_length, uint32_t subgroup_size,
                       bool shuffle_compute) {
  return strand_fits_subgroup(run_lanes(vertices_per_strand, run_length), subgroup_size, shuffle_compute);
}

uint32_t run_length_for(uint32_t guide_count, uint32_t vertices_per_strand, bool fall_back) {
  const uint64_t work = uint64_t{guide_count} * vertices_per_strand;
  if (work <= kRuns4MaxGuideVertices) return 4;
  if (work <= kRuns8MaxGuideVertices || !fall_back) return 8;
  return 0;
}

bool crowd_prefers_one_thread(uint32_t instances, uint64_t guide_vertices, uint32_t steps) {
  return steps > 0 && instances >= kCrowdMinInstances && guide_vertices >= kCrowdMinGuideVertices;
}

PassUse frame_runs_pass_use(const SceneTerms& terms, uint32_t run_length) {
  PassUse use = frame_pass_use(terms, false);
  use.info = run_length == 4 ? &kFrameRuns4 : &kFrameRuns8;
  use.features |= kRunsBit | (run_length == 4 ? kRuns4Bit : 0u);
  use.name = (run_length == 4 ? "frame(runs4)" : "frame(runs8)") + use.name.substr(5);
  return use;
}

uint32_t frame_run_length(const PassInfo* info) {
  return info == &kFrameRuns4 ? 4u : info == &kFrameRuns8 ? 8u : 0u;
}

bool is_frame_lanes(const PassInfo* info) {
  return info == &kFrameLanes || info == &kFrameLanesSubgroup || frame_run_length(info) != 0;
}

namespace {
bool is_subgroup_lanes(const PassInfo* info) {
  return info == &kFrameLanesSubgroup || frame_run_length(info) != 0;
}
// Invocations per strand.
uint32_t strand_lanes(const PassInfo* info, uint32_t vertices_per_strand) {
  if (const uint32_t run = frame_run_length(info)) return run_lanes(vertices_per_strand, run);
  return lanes_for(vertices_per_strand, 1);
}
}  // namespace

uint32_t frame_lanes_workgroup(const PassInfo* info, uint32_t vertices_per_strand, uint32_t subgroup_size,
                               uint32_t conservative_slots, bool conservative) {
  if (info == &kFrameLanesSubgroup && conservative)
    return conservative_slots * lanes_for(vertices_per_strand, 1);
  if (is_subgroup_lanes(info)) return std::max(subgroup_size, kLanesSubgroupWorkgroup);
  return lanes_for(vertices_per_strand, 32);
}

uint32_t frame_lanes_groups(const PassInfo* info, uint32_t guide_count, uint32_t vertices_per_strand,
                            uint32_t subgroup_size, uint32_t conservative_slots, bool conservative) {
  if (!is_subgroup_lanes(info)) return guide_count;
  const uint32_t per_group =
      frame_lanes_workgroup(info, vertices_per_strand, subgroup_size, conservative_slots, conservative) /
                             strand_lanes(info, vertices_per_strand);
  return (guide_count + per_group - 1) / per_group;
}

}  // namespace tressvk::sim
