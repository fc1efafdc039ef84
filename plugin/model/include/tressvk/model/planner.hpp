// The frame planner, shared by the GPU host code and the reference: it turns one frame's inputs (dt, instance
// transform, bone matrices, wind, capsules, teleport/reset) into the list of fixed-size substeps, with
// everything each substep needs in double precision and in simulation space.
//
// Simulation space: world-oriented axes, origin O = T + R * asset_origin (T, R: the instance translation and
// rotation at that substep, kept in double here). So the GPU only ever holds groom-sized numbers, and a
// character 10 km away stores the same floats as one at the origin.
//
// Time policy (docs/simulation.md): fixed step h = 1/step_rate; an accumulator collects frame time; a frame
// runs floor(accumulated/h) steps, at most max_steps_per_frame; when capped, the surplus whole steps are dropped
// and the instance motion they covered carries the hair rigidly (as a teleport does: no velocity is added), so
// the kept steps simulate the end of the frame's motion at its real speed and nothing is owed to later frames.
// The instance (and bone) motion since the last simulated step is interpolated across the frame's steps
// (lerp/slerp), so k steps see k equal slices of it. A frame with no step carries its motion over to the next
// step. A sustained low host rate is not a hitch: while the median dt of the last kRateFrames frames needs more
// steps than max_steps_per_frame, a frame may run up to max_steps_sustained (docs/simulation.md, "Time policy").
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "tressvk/model/gpu_layout.hpp"
#include "tressvk/model/math.hpp"
#include "tressvk/sim_types.h"

namespace tressvk::model {

// An affine map asset space -> simulation space (rows of a 3x4), with its rotation as a quaternion.
struct SkinTransform {
  std::array<std::array<double, 4>, 3> rows{};
  Quat rotation;
  Quat delta;  // rotation since the previous step (identity at a reset): the rigid motion VSP propagates
  // The previous step's delta, in the frame of this step's state (turned with a teleport or carry; identity after
  // a reset): VSP removes the rigid motion integration already carried as velocity.
  Quat delta_before;
  // This map minus the previous step's map carried into this step's frame (turned and shifted with the state; zero
  // at a reset): applied to a rest root, the move of that guide's anchor since the previous step, exact in double.
  std::array<std::array<double, 4>, 3> move_rows{};
  Vec3 apply(Vec3 x) const {
    return {rows[0][0] * x.x + rows[0][1] * x.y + rows[0][2] * x.z + rows[0][3],
            rows[1][0] * x.x + rows[1][1] * x.y + rows[1][2] * x.z + rows[1][3],
            rows[2][0] * x.x + rows[2][1] * x.y + rows[2][2] * x.z + rows[2][3]};
  }
};

struct CapsuleSim {
  Vec3 p0, p1;
  double r0 = 0, r1 = 0;
  Vec3 m0, m1;  // moves of p0 and p1 since the previous step, in this step's frame (zero after a reset): the
                // collider's velocity, so contacts remove only velocity relative to the surface
};

struct Substep {
  double h = 0;                 // s
  double time = 0;              // simulation time at the end of this step (s), step_counter * h
  uint32_t index = 0;           // substep index within the frame
  bool reset = false;           // put every strand at its skinned rest pose, at rest
  bool move_state = false;      // apply origin_shift and teleport to the state before integrating
  Vec3 origin_shift;            // O_now - O_before (m)
  Quat teleport;                // rotation about the origin (identity unless teleporting)
  Vec3 gravity_h2;              // g * h^2 (m)
  std::array<Vec3, 4> wind_h2;  // wind pyramid, acceleration * h^2 (m); zero without wind
  bool wind = false;
  uint32_t capsule_count = 0;
  std::array<CapsuleSim, TVK_MAX_CAPSULES> capsules{};
  bool skinned = false;             // the frame gave bones: skin holds one transform per bone the strands read
  std::vector<SkinTransform> skin;  // one per bone the strands read (set_bone_source), or one (rigid) without bones
};

struct FramePlan {
  std::vector<Substep> steps;        // may be empty (a frame shorter than the time left to the next step)
  std::array<double, 3> sim_origin{};// world position of the simulation origin after the last step (double)
  uint32_t dropped_steps = 0;        // whole steps dropped by the cap in this frame
};

// The planner's limits. The defaults are the product's (TvkTimeSettings); a converged reference (docs/accuracy.md)
// raises them, in double precision on the CPU only, to step the same model far finer than any GPU setting.
struct PlannerLimits {
  double max_step_rate = 480.0;                         // Hz
  uint32_t max_steps_per_frame = TVK_MAX_STEPS_PER_FRAME;
};

class FramePlanner {
 public:
  // asset_origin: HairAsset::origin; bone_count: the asset's bone count (0 = rigid only).
  FramePlanner(const TvkSimSettings& settings, std::array<double, 3> asset_origin, uint32_t bone_count,
               const PlannerLimits& limits = {});

  // Throws std::invalid_argument for bad input (negative dt, bone_count mismatch, too many capsules...).
  FramePlan plan(const TvkSimFrame& frame);
  // The same for a frame validate_frame has accepted (the plugin checks every frame at tressvk_set_frame).
  FramePlan plan_validated(const TvkSimFrame& frame);

  // The asset bones a plan's skin entries are, in order (ModelRest::bone_source: the bones some strand reads; empty,
  // the default: every bone of the asset). The host's frames still carry every bone; the planner validates them all
  // and works out only these, so a skinned character's CPU time scales with the bones its strands read (Ratboy's
  // mohawk: 21 of 105). Throws std::invalid_argument unless the entries are increasing asset bone indices.
  void set_bone_source(std::vector<uint32_t> source);
  // The skin entries of a skinned frame's steps.
  size_t skin_bones() const { return bone_source_.empty() ? bone_count_ : bone_source_.size(); }

  double step_length() const { return h_; }
  uint64_t steps_taken() const { return step_counter_; }
  void set_settings(const TvkSimSettings& settings);

 private:
  struct Pose {
    Vec3 t;   // world translation (double)
    Quat r;
  };
  TvkSimSettings settings_;
  PlannerLimits limits_;
  std::array<double, 3> asset_origin_;
  uint32_t bone_count_;
  std::vector<uint32_t> bone_source_;  // set_bone_source; empty: every bone
  uint32_t source_bone(size_t i) const { return bone_source_.empty() ? static_cast<uint32_t>(i) : bone_source_[i]; }
  double h_ = 0;
  double accumulator_ = 0;   // in steps
  uint64_t step_counter_ = 0;
  bool started_ = false;
  bool pending_reset_ = true;
  struct Carry {  // a pending rigid move of the state (teleport, hitch): w' = r w + t, world space
    Quat r;
    Vec3 t;
  };
  void add_carry(const Pose& from, const Pose& to);
  bool carry_pending_ = false;
  Carry carry_;
  Vec3 origin_;              // world position of the simulation origin of the state (double)
  Pose last_;                // instance pose at the last simulated step
  std::vector<Pose> last_bones_;
  Pose host_last_;           // the host's instance pose at the previous frame (steps sample between it and now)
  std::vector<Pose> host_last_bones_;
  std::vector<Quat> last_rot_;  // skin rotations of the last planned step
  std::vector<Quat> last_delta_;  // skin deltas of the last planned step
  std::vector<std::array<std::array<double, 4>, 3>> last_rows_;  // skin maps of the last planned step
  std::vector<CapsuleSim> last_caps_;  // capsules of the last planned step (its frame)
  // The host's recent frame lengths (frames with dt > 0), for telling a sustained low rate from a hitch.
  static constexpr uint32_t kRateFrames = 8;
  std::array<double, kRateFrames> recent_dt_{};
  uint32_t recent_count_ = 0;
  uint32_t frame_cap(double dt);  // records dt; the most steps this frame may plan, a reset step included
};

// Checks every host number of a frame: dt, the transform, bone matrices, capsules and wind must be finite, rotations
// (near-)unit quaternions, radii >= 0, counts within limits. Throws std::invalid_argument naming the field (e.g.
// "capsules[1].r0 is not finite"). asset_bone_count: the asset's bones (0 = rigid only).
void validate_frame(const TvkSimFrame& frame, uint32_t asset_bone_count);

// Per-group parameters converted to per-step values for step length h (what both sides use).
struct GroupStep {
  double velocity_keep = 1;    // exp(-damping * h * 60)
  double global_stiffness = 0; // 0 when range or stiffness is 0
  double global_range = 0;
  double local_stiffness = 0;  // 0.5 * min(s, 0.95)
  uint32_t local_iterations = 0;  // 0 when stiffness is 0
  uint32_t length_iterations = 1;
  double vsp_coefficient = 0;  // 0 = no VSP for this group
  double vsp_threshold = 0;    // a * h^2
  double max_step = 0;         // max_speed * h, 0 = off
  double tip_separation = 0;   // resolved against the asset's
  double rigid_below = 0;      // m, resolved against the asset's median strand length (0 = none)
};
// Throws std::invalid_argument for out-of-range values (naming the field). asset_median_length: the asset's median
// strand length (ModelRest::median_length), which a negative rigid_below is a fraction of. Takes resolved parameters
// (resolve_params): TVK_ITERATIONS_BY_MODEL is refused here.
GroupStep to_group_step(const TvkSimParams& params, double h, double asset_tip_separation, double asset_median_length);

// The conversions the host uploads: everything the shaders read per frame.
struct GpuFrame {
  std::vector<sim::StepParams> steps;  // one per substep
  std::vector<sim::Vec4> skin;         // steps * bones_per_step * kSkinVec4PerBone (substep s at s * skin_stride)
  uint32_t skin_stride = 0;            // vec4 per substep
};
GpuFrame to_gpu(const FramePlan& plan);
// The same into `out`, whose storage it reuses.
void to_gpu_into(const FramePlan& plan, GpuFrame& out);
sim::GroupParams to_gpu(const GroupStep& group);

// ---- The strand models (TvkSimSettings::model; the reference's SimModel) -------------------------------------------
// The compliant model (docs/accuracy.md, "The compliant model") runs on the lane-parallel frame kernel
// (shaders/sim/frame_lanes.comp); the conservative model is the compliant model with the conservative local shape
// (the reference's LengthModel::kConservative; the lane kernel's conservative variant, lanes_compliant.glsl), and
// shares its uploads and length solve.
enum class StrandModel { kFollowTheLeader, kCompliant, kConservative };
// The model an instance (or a reference Simulator) with these settings runs: TvkSimSettings::model, where that is
// TVK_SIM_MODEL_DEFAULT the TRESSVK_SIM_MODEL environment variable's model (read once per process; follow-the-leader
// when unset), so that a test run with the variable set compares like with like on the GPU and the reference.
StrandModel resolve_model(TvkSimModel model);
// The same as the public enum: the model TVK_SIM_MODEL_DEFAULT stands for named (what tressvk_get_sim_settings reports).
TvkSimModel resolved_sim_model(TvkSimModel model);
inline bool is_compliant_family(StrandModel m) { return m != StrandModel::kFollowTheLeader; }
// What TVK_STEP_RATE_BY_MODEL and TVK_ITERATIONS_BY_MODEL mean for a model and strands of n vertices: the rate and
// local iteration count each model is made for (docs/accuracy.md, "Which model, at which rate"): follow-the-leader
// and compliant 240 Hz with 2 iterations (the settings follow-the-leader's look is tuned at); conservative 1
// iteration (its shape hardly depends on the count) at 120 Hz for up to 64 vertices, 240 Hz above (where 120 Hz
// fails the 128-vertex hard case).
float model_step_rate(StrandModel m, uint32_t vertices_per_strand);
uint32_t model_local_iterations(StrandModel m);
// The settings and parameters with every "by model" value replaced by the model's; anything else as given. Both
// sides resolve before they plan or convert, so an instance and a reference Simulator of the same model agree.
TvkSimSettings resolve_settings(const TvkSimSettings& settings, StrandModel m, uint32_t vertices_per_strand);
TvkSimParams resolve_params(const TvkSimParams& params, StrandModel m);
// kConservative's compliance per edge: compliant_bend_alpha_base x this x (31 a / L)^4; its damping time: the
// compliant model's per-edge time x kConservativeDampingScale (reference simulator.cpp, lanes_compliant.glsl).
inline constexpr double kConservativeCalibration = 0.080;
inline constexpr double kConservativeDampingScale = 0.3;
// Global shape: the spring's fraction k h^2 / (1 + k h^2) at step h, k = s / ((1 - s) h0^2), h0 = 1/240 s.
double compliant_global_fraction(double s, double h);
// Local shape: alpha / h^2 of an edge of the calibration length (the strand's length / 31) at step h, from the
// per-iteration fraction s' = GroupStep::local_stiffness; an edge of rest length a on a strand of length L has
// alpha / h^2 = compliant_bend_alpha_base(s', h) (31 a / L)^3.
double compliant_bend_alpha_base(double s_step, double h);
// The bending constraints' damping gamma = tau / h.
double compliant_bend_damping(double h);
// The group's GPU parameters for the compliant kernel: global_stiffness = the spring's fraction at h, reserved0 =
// compliant_bend_alpha_base, reserved1 = compliant_bend_damping.
sim::GroupParams to_gpu_compliant(const GroupStep& group, double h);

}  // namespace tressvk::model
