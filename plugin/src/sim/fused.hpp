// The frame kernels: one dispatch per instance per frame running every substep and every pass the scene needs, the
// strand's state on chip. Follow-the-leader (the default model) has two, which give the same float results: the run
// kernel (shaders/sim/frame_runs.glsl, a run of 4 or 8 vertices a lane; the default up to 768 k guide vertices) and
// the one-thread kernel (shaders/sim/frame.glsl, a strand a thread; larger grooms, strands pinned at their tip). The
// compliant model has the lane kernel (frame_lanes.glsl). The pass-per-dispatch path (passes.hpp, one dispatch per
// pass per substep) stays behind TRESSVK_SIM_PATH=passes as a debugging aid that times each pass on its own
// (docs/simulation.md).
#pragma once

#include <cstdint>

#include "sim/passes.hpp"

namespace tressvk::sim {

enum class SimPath : uint32_t {
  kAuto,         // the default: kRuns up to 768 k guide vertices (run_length_for) where the runs fit the subgroup
                 // and no strand is pinned at its tip, else kFused
  kRuns,         // the run kernel (frame_runs.comp) wherever it fits and no strand is pinned at its tip, else kFused
  kFused,        // frame.comp: one thread per strand, the strand in private arrays
  kFusedShared,  // frame_shared.comp: the strand block in shared memory (where it fits, else kFused)
  kPasses,       // one dispatch per pass per substep
};

// TRESSVK_SIM_PATH = "runs", "fused", "fused-shared" or "passes"; read once per process. Anything else: kAuto.
SimPath sim_path_from_environment();

// Shared memory the shared-memory variant needs for N vertices per strand (positions and history; VSP's second
// history lives in registers).
uint32_t frame_shared_bytes(uint32_t vertices_per_strand, bool vsp);

// The frame pass of a scene: FEATURES = the scene's feature bits plus kFeatureVsp / kFeatureLocalShape.
// shared: the shared-memory variant (the caller checked that it fits).
// guide_count: the instance's guides, which choose the one-thread kernel's workgroup (0: the narrow one).
PassUse frame_pass_use(const SceneTerms& terms, bool shared, uint32_t guide_count = 0);

// Workgroups of the frame pass: one per 32 guides (a strand block), or per 512 for the one-thread kernel's wide
// variant (frame_private_workgroup).
uint32_t frame_dispatch_groups(const PassUse& use, uint32_t guide_count);
// The one-thread kernel (frame.comp, frame_follows.comp) runs in workgroups of 32 threads, or of 512 from
// kFrameWideMinGuides guides (named "frame(wide)"): a workgroup of 512 holds the driver to 128 registers a thread
// (fused.cpp has the measurements). TRESSVK_SIM_FRAME_WG=32|512 forces either.
constexpr uint32_t kFrameWideWorkgroup = 512;
constexpr uint32_t kFrameWideMinGuides = 64u * 1024u;
uint32_t frame_private_workgroup(const PassUse& use);
bool is_frame_private(const PassInfo* info);

// The compliant model's lane-parallel frame kernel (frame_lanes.glsl, TRESSVK_SIM_MODEL=compliant), one lane per
// vertex, in two variants: subgroup (a strand is a cluster of lanes of one subgroup, values move by shuffles;
// frame_lanes_subgroup.comp) where lanes_fit_subgroup, else shared (one strand per workgroup, values through shared
// memory; frame_lanes.comp). TRESSVK_SIM_LANES=shared (read once per process) keeps the shared variant everywhere.
// It records as the frame pass (PassId::kFrame) with its own pipeline.
enum class LanesBackend { kAuto, kShared };
LanesBackend lanes_backend_from_environment();
// The power of two >= N fits the subgroup, and compute shaders may shuffle and vote.
bool lanes_fit_subgroup(uint32_t vertices_per_strand, uint32_t subgroup_size, bool shuffle_compute);
// With the conservative local shape (TVK_SIM_MODEL_CONSERVATIVE) the subgroup variant keeps its strands' systems
// in shared memory: the strands a workgroup (whole subgroups, at most 384 invocations) that the device's limits allow
// (maxComputeWorkGroupInvocations, the lesser of it and maxComputeWorkGroupSize[0]; maxComputeSharedMemorySize), 0
// where not one subgroup's worth fits (the shared variant then).
uint32_t conservative_slots(uint32_t vertices_per_strand, uint32_t subgroup_size, uint32_t max_invocations,
                            uint32_t max_shared_bytes);
// conservative: the conservative local shape (kFeatureConservative, its own pipelines), else the compliant model's.
// refinements (with conservative): its shape solve refined 0, 1 or 3 times (kFeatureRefine, kFeatureRefineThrice,
// lanes_compliant.glsl): conservative_refinements.
PassUse frame_lanes_pass_use(const SceneTerms& terms, bool subgroup, bool conservative, uint32_t refinements);
// The step rate below which the conservative local shape's solve is refined once. The float factorisation of a stiff
// strand's system loses more digits the longer the step (its compliance goes as the step squared): at 60 Hz and 1
// iteration five of the hard cases missed the 1e-5 step-error bar without the refinement, 14 of 15 pass with it
// (lavapipe and an NVIDIA H100); at 120 Hz and above the plain solve passes the same 14 (240 Hz: all 15), and the
// refinement would cost 26-46 % of the frame (NVIDIA H100, docs/accuracy.md, "The shape solve refined").
constexpr float kConservativeRefineBelowHz = 120.0f;
// The step rate below which it is refined three times. Each refinement divides the solve's float error by about
// (the factor's float error) x (the system's condition), which grows as the step squared: strands pinned at both
// ends, shaken at 30 Hz steps with 1 iteration (lavapipe), read 9.7e-4 unrefined, 2.2e-4 refined once, 2.9e-5
// twice, 1.3e-6 three times and 1.9e-7 four times, where at 60 Hz once takes them from 6.3e-5 to 1.6e-7.
constexpr float kConservativeRefineThriceBelowHz = 60.0f;
// The slowest step rate at which the conservative local shape is recommended for strands of n vertices: 60 Hz, and
// 240 Hz for more than 64 vertices. Slower, the hard cases fail (NVIDIA H100 and lavapipe, 1 local iteration: 30 Hz
// passes 8 of 15; 128-vertex strands miss the step-error bar at 60 and 120 Hz, where the model amplifies a state's
// rounding), and an instance created or set there gets a warning (docs/accuracy.md, "Which model, at which rate").
constexpr float conservative_least_rate(uint32_t n) { return n > 64u ? 240.0f : 60.0f; }
// How many times an instance stepping at step_rate refines the conservative local shape's solve.
constexpr uint32_t conservative_refinements(float step_rate) {
  return step_rate < kConservativeRefineThriceBelowHz ? 3u : step_rate < kConservativeRefineBelowHz ? 1u : 0u;
}
// The same, unless TRESSVK_SIM_REFINE = "0", "1" or "3" (read once per process) forces the count: a diagnostic, to
// time and compare the counts on one build.
uint32_t conservative_refinements_for(float step_rate);
bool is_frame_lanes(const PassInfo* info);

// The follow-the-leader model's run kernel (frame_runs.glsl): each lane holds a run of 4 or 8 consecutive vertices
// (RUN, specialisation constant 5), a strand is a cluster of RL = the power of two >= ceil(N / RUN) lanes of one
// subgroup; subgroup shuffles only. It records as the frame pass; is_frame_lanes, frame_lanes_workgroup and
// frame_lanes_groups cover it.
// TRESSVK_SIM_RUN = "4" or "8" (read once per process) forces the run length; 0 when unset.
uint32_t run_length_from_environment();
// The run length for a groom (4 up to 160 k guide vertices, 8 above), or 0 (the one-thread kernel) above 768 k when
// fall_back: the crossovers measured on an NVIDIA H100 (fused.cpp).
uint32_t run_length_for(uint32_t guide_count, uint32_t vertices_per_strand, bool fall_back);
// A frame of a tressvk_cmd_simulate call whose follow-the-leader instances number `instances` and hold
// `guide_vertices` between them, with `steps` steps: true where the measured crossovers (fused.cpp) put the
// one-thread kernel ahead of each instance's own run kernel (4 instances and 400 k guide vertices, at any step rate;
// a frame without steps runs nothing).
bool crowd_prefers_one_thread(uint32_t instances, uint64_t guide_vertices, uint32_t steps);
// RL lanes fit the subgroup, and compute shaders may shuffle and vote.
bool runs_fit_subgroup(uint32_t vertices_per_strand, uint32_t run_length, uint32_t subgroup_size,
                       bool shuffle_compute);
PassUse frame_runs_pass_use(const SceneTerms& terms, uint32_t run_length);
// RUN of the frame pass (4 or 8), 0 for any other pass.
uint32_t frame_run_length(const PassInfo* info);
// Its workgroup size (WORKGROUP_SIZE): shared, the power of two >= N, at least 32; subgroup, whole subgroups, at
// least 64 invocations (with the conservative local shape, `conservative`, conservative_slots strands). And its
// workgroups for G guides.
uint32_t frame_lanes_workgroup(const PassInfo* info, uint32_t vertices_per_strand, uint32_t subgroup_size,
                               uint32_t conservative_slots, bool conservative);
uint32_t frame_lanes_groups(const PassInfo* info, uint32_t guide_count, uint32_t vertices_per_strand,
                            uint32_t subgroup_size, uint32_t conservative_slots, bool conservative);

}  // namespace tressvk::sim
