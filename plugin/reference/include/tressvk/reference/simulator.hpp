// The CPU reference simulator: the TressVK model in double precision, pass for pass and in the same order of
// operations as shaders/sim/*.comp (integrate, vsp, local_shape, length per substep; follow once per frame).
//
// Typical uses:
// - trajectory: construct, then advance(frame) every frame (it plans with its own FramePlanner);
// - one-frame step error against the GPU: plan once with a shared FramePlanner, record the GPU frame from
//   to_gpu(plan), set_state() from the GPU state read back before the frame, simulate(plan), compare.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <tressvk/asset.hpp>

#include "tressvk/model/model.hpp"
#include "tressvk/model/planner.hpp"
#include "tressvk/sim_types.h"

namespace tressvk::reference {

// The reference is written in the runtime model's terms (planner, rest data, math: tressvk::model).
using namespace tressvk::model;

class Simulator {
 public:
  // group_params: one per strand group of the asset (a single entry is used for every group).
  // Throws std::invalid_argument for an inconsistent asset or out-of-range parameters.
  // limits: the planner's; raised only for a converged reference (step rates beyond what the GPU is given).
  Simulator(const asset::HairAsset& asset, std::span<const TvkSimParams> group_params,
            const TvkSimSettings& settings, const PlannerLimits& limits = {});

  void set_params(std::span<const TvkSimParams> group_params);

  // The length constraints' scheme. kFollowTheLeader (the default, what the GPU runs): follow-the-leader with the
  // DFTL velocity correction (tip-pinned strands: a tridiagonal Newton solve). kNewmark (reference only, opt-in):
  // every strand by a tridiagonal Newton solve with an implicit transverse response (the average-acceleration rule):
  // a hanging chain's period within 0.05 % of the discrete value and <= 0.4 % amplitude loss per period at damping 0
  // for N 16-64 at 60-480 Hz (N 64 at 60 Hz: -2.1 %, 5.9 %), where DFTL gives -7 to -29 % and 58 % loss. Not the
  // default yet: local shape adds energy at few iterations, which DFTL's damping hid (the curly rest pose without
  // gravity grows from rounding by about x1.034 per step at 2 local iterations, 0.31 L in 2 s at 1), and the GPU has
  // no twin (docs/accuracy.md).
  //
  // kCompliant (opt-in: set_model, or TRESSVK_SIM_MODEL=compliant as every Simulator's default; GPU twin:
  // shaders/sim/frame_lanes.comp): the lane-parallel model. Every per-substep solve is parallel over the vertices of a
  // strand (a scan or a tridiagonal system: parallel cyclic reduction over the lanes on the GPU) and every stiffness
  // means the same whatever N, step rate and iteration count. Global shape: a spring toward the skinned rest pose
  // (global_stiffness = its fraction per step at 240 Hz). Local shape: XPBD vector constraints x_{v+1} - x_v = T_v,
  // T_v the skinned rest edge turned by the minimal rotation of the edge before it from its skinned rest direction
  // (a local frame: no transport along the whole strand), with a compliance per edge of a^3 / B, all of a strand's
  // constraints solved at once per iteration (a tridiagonal system, targets held), the multipliers accumulated over
  // the substep, a damping time of 5 ms on the constraints; local_stiffness maps to B so that a cantilever sags as it
  // did at 240 Hz, 2 iterations, 32 vertices (tressvk::model::compliant_*). Length: the Newmark model's Newton step
  // and implicit transverse response, then length_iterations more Newton steps (up to 4 more while a segment is off by
  // > 1e-3), with no serial clean-up. Measured (docs/accuracy.md): cantilever sag within 10 % over N 16-128,
  // 120-480 Hz and 1-8 iterations (60 Hz: +12.7 %), where the follow-the-leader model spreads over 6x.
  //
  // kConservative (opt-in: set_model, or TRESSVK_SIM_MODEL=conservative; GPU twin: lanes_compliant.glsl,
  // local_shape_lanes_conservative, slow): kCompliant with a conservative local shape. kCompliant
  // holds each constraint's target while it solves, so the target's dependence on the edge before it has no reaction:
  // the shape force is not the gradient of an energy, and it pumps energy into curls (the curly groom's trajectory
  // stops converging as h shrinks: docs/accuracy.md). Here the same constraints are solved with their full gradient:
  // C_v = x_{v+1} - x_v - T_v(x_{j+1} - x_j) (j: the frame edge before v), dT/de = ((T.u) I - u T^T) / |e| (the
  // target turns with its frame edge; its twist about that edge is left out), so each constraint touches four
  // vertices and the system is block (3x3) pentadiagonal: a banded Cholesky solve per strand per iteration (the
  // reaction is taken where the frame edge is the edge just before, so that the band is the same everywhere). The
  // constraint then carries the bending moment (not the shear load), so the compliance per edge is a^4 / B and the
  // calibration is its own (the same cantilever sag at 240 Hz, 2 iterations, 32 vertices).
  enum class LengthModel { kFollowTheLeader, kNewmark, kCompliant, kConservative };
  using SimModel = LengthModel;
  // A change of model re-resolves what the settings and parameters leave to it (TVK_STEP_RATE_BY_MODEL,
  // TVK_ITERATIONS_BY_MODEL), as an instance's tressvk_set_sim_settings does; kNewmark takes follow-the-leader's.
  void set_length_model(LengthModel m) { set_model(m); }
  void set_model(SimModel m);
  SimModel model() const { return length_model_; }
  const std::vector<TvkSimParams>& params() const { return params_; }
  const ModelRest& rest() const { return rest_; }
  FramePlanner& planner() { return planner_; }

  // Loads float state as the GPU holds it: pos has G*N (guides) or G*(K+1)*N entries, prev and prevprev G*N.
  // The w components are ignored (inverse masses come from the asset).
  void set_state(std::span<const sim::Vec4> pos, std::span<const sim::Vec4> prev, std::span<const sim::Vec4> prevprev);
  // The same from double positions (e.g. a GPU state held as per-strand anchor + float offset, summed in double).
  void set_state(std::span<const Vec3> pos, std::span<const Vec3> prev, std::span<const Vec3> prevprev);
  using Point = std::array<double, 3>;  // e.g. tressvk::host::HairState's positions
  void set_state(std::span<const Point> pos, std::span<const Point> prev, std::span<const Point> prevprev);

  // Runs every substep of the plan, then the follow update (when the plan has steps).
  void simulate(const FramePlan& plan);
  // Plans with the simulator's own planner, then simulates. Returns the plan.
  FramePlan advance(const TvkSimFrame& frame);

  // The passes one by one (what simulate() calls), for per-pass tests.
  void integrate(const Substep& step);
  void vsp(const Substep& step);
  void local_shape(const Substep& step);
  void local_shape_compliant(const Substep& step);
  void length_and_collision(const Substep& step);
  void follow(const Substep& step);

  // State, simulation space. positions(): G*(K+1)*N (guides, then follow layers); prev/prevprev: G*N.
  std::span<const Vec3> positions() const { return pos_; }
  std::span<Vec3> mutable_positions() { return pos_; }  // fault injection in tests
  std::span<const Vec3> prev_positions() const { return prev_; }
  std::span<const Vec3> prevprev_positions() const { return prevprev_; }
  std::span<const Vec3> tangents() const { return tangent_; }
  // Strands reset to the rest pose after going non-finite, since construction.
  uint64_t nonfinite_resets() const { return nonfinite_resets_; }
  double median_strand_length() const { return rest_.median_length; }
  // Skinned rest position of guide vertex i at a substep.
  Vec3 skinned_rest(const Substep& step, size_t vertex) const;

 private:
  const GroupStep& group_of(uint32_t guide) const { return steps_params_[rest_.group[guide]]; }
  void prepare_groups(double h);
  Quat skin_rotation(const Substep& step, uint32_t g) const;
  Quat skin_delta(const Substep& step, uint32_t g) const;
  Quat skin_delta_before(const Substep& step, uint32_t g) const;
  Quat current_root_frame(const Substep& step, uint32_t g) const;
  StrandModel strand_model() const;  // what the settings' "by model" values resolve by
  bool compliant_model() const {
    return length_model_ == LengthModel::kCompliant || length_model_ == LengthModel::kConservative;
  }
  void local_shape_conservative(const Substep& st);
  void shape_targets(size_t strand_base, const Quat& skin, std::vector<int>* frame_edge = nullptr);
  double shape_weight(size_t vertex, const GroupStep& gp, double h) const;

  ModelRest rest_;                     // inv_mass: with each group's rigid_below applied
  std::vector<double> asset_inv_mass_;  // the asset's own pins
  TvkSimSettings host_settings_;       // as given: the planner holds them resolved for the model
  std::vector<TvkSimParams> params_;   // as given: steps_params_ are resolved for the model
  std::vector<GroupStep> steps_params_;
  double prepared_h_ = -1;
  FramePlanner planner_;
  bool skinned_ = false;  // the current substep blends bones
  std::vector<Vec3> pos_, prev_, prevprev_, tangent_;
  uint64_t nonfinite_resets_ = 0;
  // One Newton step of a strand's length constraints (solve_lengths, every strand): per segment, c' and d' (then
  // lambda). weight (0..1) scales the step (before its reach limit).
  void solve_lengths(size_t strand_base, double weight = 1.0);
  // The implicit transverse correction after the Newton steps (see simulator.cpp).
  void implicit_transverse(size_t strand_base, double alpha);
  std::vector<double> seg_cp_, seg_dp_;
  LengthModel length_model_ = LengthModel::kFollowTheLeader;
  std::vector<double> lam_;  // the Newton steps' multipliers summed, per segment
  std::vector<Vec3> move_, tdp_;
  std::vector<Vec3> lam3_, frame_dir_;  // kCompliant: shape multipliers per edge; per-edge directions
  std::vector<Vec3> targets_;           // kCompliant: each shape constraint's target edge
  std::vector<double> band_, band_rhs_;  // kConservative: the banded system and its right-hand side
  std::vector<Vec3> carried_;            // kConservative: each vertex's move by the head's turn of this step
};

}  // namespace tressvk::reference
