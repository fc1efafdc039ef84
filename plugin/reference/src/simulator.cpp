#include "tressvk/reference/simulator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tressvk::reference {

Simulator::Simulator(const asset::HairAsset& asset, std::span<const TvkSimParams> group_params,
                     const TvkSimSettings& settings, const PlannerLimits& limits)
    : rest_(build_model_rest(asset)),
      host_settings_(settings),
      planner_(resolve_settings(settings, resolve_model(settings.model), rest_.vertices_per_strand), asset.origin,
               rest_.asset_bone_count, limits) {
  planner_.set_bone_source(rest_.bone_source);  // the bones the strands read, as the plugin's instances plan them
  asset_inv_mass_ = rest_.inv_mass;
  switch (resolve_model(settings.model)) {
    case StrandModel::kCompliant: length_model_ = LengthModel::kCompliant; break;
    case StrandModel::kConservative: length_model_ = LengthModel::kConservative; break;
    case StrandModel::kFollowTheLeader: break;
  }
  set_params(group_params);
  const size_t n_all = size_t{rest_.guide_count} * (rest_.follow_per_guide + 1) * rest_.vertices_per_strand;
  pos_.assign(n_all, Vec3{});
  tangent_.assign(n_all, Vec3{});
  prev_.assign(rest_.rest_pos.size(), Vec3{});
  prevprev_.assign(rest_.rest_pos.size(), Vec3{});
  seg_cp_.assign(rest_.vertices_per_strand, 0.0);
  seg_dp_.assign(rest_.vertices_per_strand, 0.0);
  lam_.assign(rest_.vertices_per_strand, 0.0);
  move_.assign(rest_.vertices_per_strand, Vec3{});
  carried_.assign(rest_.vertices_per_strand, Vec3{});
  tdp_.assign(rest_.vertices_per_strand, Vec3{});
  lam3_.assign(rest_.vertices_per_strand, Vec3{});
  frame_dir_.assign(rest_.vertices_per_strand, Vec3{});
  targets_.assign(rest_.vertices_per_strand, Vec3{});
}

void Simulator::set_params(std::span<const TvkSimParams> group_params) {
  if (group_params.empty()) throw std::invalid_argument("reference: no group parameters given");
  params_.assign(group_params.begin(), group_params.end());
  if (params_.size() == 1 && rest_.group_count > 1) params_.resize(rest_.group_count, params_.front());
  if (params_.size() < rest_.group_count) {
    throw std::invalid_argument("reference: " + std::to_string(params_.size()) + " group parameter sets for " +
                                std::to_string(rest_.group_count) + " strand groups");
  }
  prepared_h_ = -1;
  prepare_groups(planner_.step_length());
}

StrandModel Simulator::strand_model() const {
  switch (length_model_) {
    case LengthModel::kCompliant: return StrandModel::kCompliant;
    case LengthModel::kConservative: return StrandModel::kConservative;
    case LengthModel::kFollowTheLeader:
    case LengthModel::kNewmark: break;
  }
  return StrandModel::kFollowTheLeader;
}

void Simulator::set_model(SimModel m) {
  length_model_ = m;
  if (host_settings_.time.step_rate == TVK_STEP_RATE_BY_MODEL)
    planner_.set_settings(resolve_settings(host_settings_, strand_model(), rest_.vertices_per_strand));
  prepared_h_ = -1;
  prepare_groups(planner_.step_length());
}

void Simulator::prepare_groups(double h) {
  if (h == prepared_h_) return;
  steps_params_.clear();
  for (const TvkSimParams& p : params_)
    steps_params_.push_back(
        to_group_step(resolve_params(p, strand_model()), h, rest_.asset_tip_separation, rest_.median_length));
  prepared_h_ = h;
  // Each group's rigid_below: its short strands take inverse mass 0 at every vertex, the others the asset's (the GPU
  // applies the same rule as it integrates, strand_rigid in common.glsl).
  const uint32_t n = rest_.vertices_per_strand;
  for (uint32_t g = 0; g < rest_.guide_count; ++g) {
    const bool rigid = rigid_by_rule(rest_.strand_length[g], steps_params_[rest_.group[g]].rigid_below);
    for (uint32_t v = 0; v < n; ++v) {
      const size_t i = size_t{g} * n + v;
      rest_.inv_mass[i] = rigid ? 0.0 : asset_inv_mass_[i];
    }
  }
}

void Simulator::set_state(std::span<const sim::Vec4> pos, std::span<const sim::Vec4> prev,
                          std::span<const sim::Vec4> prevprev) {
  const size_t guides = rest_.rest_pos.size();
  if ((pos.size() != guides && pos.size() != pos_.size()) || prev.size() != guides || prevprev.size() != guides) {
    throw std::invalid_argument("reference: set_state sizes do not match the asset");
  }
  auto widen = [](const sim::Vec4& v) { return Vec3{v[0], v[1], v[2]}; };
  for (size_t i = 0; i < pos.size(); ++i) pos_[i] = widen(pos[i]);
  for (size_t i = 0; i < guides; ++i) {
    prev_[i] = widen(prev[i]);
    prevprev_[i] = widen(prevprev[i]);
  }
}

void Simulator::set_state(std::span<const Vec3> pos, std::span<const Vec3> prev, std::span<const Vec3> prevprev) {
  const size_t guides = rest_.rest_pos.size();
  if ((pos.size() != guides && pos.size() != pos_.size()) || prev.size() != guides || prevprev.size() != guides) {
    throw std::invalid_argument("reference: set_state sizes do not match the asset");
  }
  std::copy(pos.begin(), pos.end(), pos_.begin());
  std::copy(prev.begin(), prev.end(), prev_.begin());
  std::copy(prevprev.begin(), prevprev.end(), prevprev_.begin());
}

void Simulator::set_state(std::span<const Point> pos, std::span<const Point> prev, std::span<const Point> prevprev) {
  auto widen = [](std::span<const Point> in) {
    std::vector<Vec3> out(in.size());
    for (size_t i = 0; i < in.size(); ++i) out[i] = {in[i][0], in[i][1], in[i][2]};
    return out;
  };
  const std::vector<Vec3> p = widen(pos), q = widen(prev), r = widen(prevprev);
  set_state(std::span<const Vec3>(p), std::span<const Vec3>(q), std::span<const Vec3>(r));
}

FramePlan Simulator::advance(const TvkSimFrame& frame) {
  FramePlan plan = planner_.plan(frame);
  simulate(plan);
  return plan;
}

void Simulator::simulate(const FramePlan& plan) {
  bool any_vsp = false, any_local = false;
  for (const Substep& st : plan.steps) {
    prepare_groups(st.h);
    any_vsp = any_local = false;
    for (const GroupStep& g : steps_params_) {
      any_vsp = any_vsp || g.vsp_coefficient > 0;
      any_local = any_local || g.local_iterations > 0;
    }
    integrate(st);
    if (any_vsp) vsp(st);
    if (any_local) {
      if (compliant_model()) {
        if (length_model_ == LengthModel::kConservative) local_shape_conservative(st);
        else local_shape_compliant(st);
      } else {
        local_shape(st);
      }
    }
    length_and_collision(st);
  }
  if (!plan.steps.empty() && rest_.follow_per_guide > 0) follow(plan.steps.back());
}

Vec3 Simulator::skinned_rest(const Substep& st, size_t i) const {
  const uint32_t n = rest_.vertices_per_strand;
  const Vec3 x = rest_.rest_pos[i];
  if (st.skinned) {
    const uint32_t g = static_cast<uint32_t>(i / n);
    std::array<std::array<double, 4>, 3> r{};
    for (size_t k = 0; k < 4; ++k) {
      double w = rest_.bone_weight[g][k];
      if (w == 0.0) continue;
      const SkinTransform& t = st.skin[rest_.bone_index[g][k]];
      for (size_t row = 0; row < 3; ++row) {
        for (size_t c = 0; c < 4; ++c) r[row][c] += w * t.rows[row][c];
      }
    }
    return {r[0][0] * x.x + r[0][1] * x.y + r[0][2] * x.z + r[0][3],
            r[1][0] * x.x + r[1][1] * x.y + r[1][2] * x.z + r[1][3],
            r[2][0] * x.x + r[2][1] * x.y + r[2][2] * x.z + r[2][3]};
  }
  return st.skin.front().apply(x);
}

Quat Simulator::skin_rotation(const Substep& st, uint32_t g) const {
  if (st.skinned) {
    const Quat q0 = st.skin[rest_.bone_index[g][0]].rotation;
    Quat q{0, 0, 0, 0};
    for (size_t k = 0; k < 4; ++k) {
      double w = rest_.bone_weight[g][k];
      if (w == 0.0) continue;
      const Quat qi = st.skin[rest_.bone_index[g][k]].rotation;
      double s = dot(qi, q0) < 0.0 ? -w : w;
      q = {q.x + s * qi.x, q.y + s * qi.y, q.z + s * qi.z, q.w + s * qi.w};
    }
    return normalize(q);
  }
  return st.skin.front().rotation;
}

namespace {
// Blends one per-bone rotation (`member` of each bone's SkinTransform) with the strand's bone weights; the GLSL
// twin is blend_bone_delta in common.glsl.
Quat blend_bone_delta(const Substep& st, const ModelRest& rest, uint32_t g, Quat SkinTransform::*member) {
  if (st.skinned) {
    Quat q{0, 0, 0, 0};
    for (size_t k = 0; k < 4; ++k) {
      const double w = rest.bone_weight[g][k];
      if (w == 0.0) continue;
      const Quat qi = st.skin[rest.bone_index[g][k]].*member;
      q = {q.x + w * qi.x, q.y + w * qi.y, q.z + w * qi.z, q.w + w * qi.w};
    }
    return normalize(q);
  }
  return st.skin.front().*member;
}
}  // namespace

Quat Simulator::skin_delta(const Substep& st, uint32_t g) const {
  return blend_bone_delta(st, rest_, g, &SkinTransform::delta);
}

Quat Simulator::skin_delta_before(const Substep& st, uint32_t g) const {
  return blend_bone_delta(st, rest_, g, &SkinTransform::delta_before);
}

Quat Simulator::current_root_frame(const Substep& st, uint32_t g) const {
  const size_t b = size_t{g} * rest_.vertices_per_strand;
  Quat f = quat_mul(skin_rotation(st, g), rest_.root_frame[g]);
  if (rest_.frame_turns[b + 1]) f = frame_align(f, pos_[b + 1] - pos_[b], rest_.rest_length[b]);
  return f;
}

// ---- The compliant model's constants (SimModel::kCompliant): tressvk::model (planner.hpp), shared with the plugin.
namespace {
// The compliant length solve's safeguard (see length_and_collision).
constexpr uint32_t kCompliantExtraNewton = 4;
// LengthModel::kConservative's length fallback: a follow-the-leader clean-up whose move is weighted from 0 where the
// worst segment is off its length by kConservativeFallbackStretch to whole at twice that (length_and_collision).
constexpr double kConservativeFallbackStretch = 4e-3;
constexpr double kCompliantStretchTol = 1e-3;
// The damped Newton step's reach is measured against segments of at least this fraction of the strand's mean segment
// (see solve_lengths).
constexpr double kCompliantReachFloorRel = 0.5;
constexpr double kCalibrationSegments = 31.0;

// Local shape: the dimensionless XPBD compliance alpha / h^2 of one edge's vector constraint C_v = x_{v+1} - x_v -
// F_v e_v (unit mass per free vertex). Each constraint carries the shear load beyond it (lambda_v / h^2 = g times the
// vertices beyond v, at rest), so with a per-edge compliance a^3 / B the angle at vertex v is a g (L - s) / B and the
// tip of a horizontal strand sinks by g L^3 / (3 B) whatever N: B (m^3/s^2 per unit mass per length) is the strand's
// shape stiffness, and its meaning does not change with N, h or the iteration count (the solve is exact). B per strand
// from local_stiffness s: the compliance that removes the same fraction of an isolated edge's error per step as the
// follow-the-leader model's two Gauss-Seidel iterations at h0 = 1/240 s (1 - (1 - 2 s')^2, s' = 0.5 min(s, 0.95)),
// for the strand's length divided into 31 edges, times a calibration factor (planner.cpp):
//   alpha / h^2 = c (2 / rho - 2) (31 a / L)^3 (h0 / h)^2.
double compliant_bend_alpha(double s_step, double edge, double strand_length, double h) {
  const double rel = kCalibrationSegments * edge / strand_length;
  return compliant_bend_alpha_base(s_step, h) * (rel * rel * rel);
}

// kConservative's compliance per edge: its constraints carry the bending moment (angle at v = alpha M / a^2), so
// a^4 / B keeps the sag independent of N; kConservativeCalibration puts the cantilever's sag (L 0.2 m, 2 root vertices
// pinned, defaults, 240 Hz, 2 iterations, 32 vertices) at kCompliant's (tressvk_accuracy_probe cantilever).
// (kConservativeCalibration: planner.hpp, times compliant_bend_alpha_base, kBendCalibration 5.4.)
// kConservative's damping: kCompliant's damping time per edge times this (1.5 ms at the calibration edge), on the
// constraints' own rate G (x - prev - carried), carried the head's turn of the step (a strand turning with the head is
// not damped: local_shape_conservative). kCompliant needs 5 ms to take out the
// energy its held targets put in; here the curly groom's trajectory converges as h halves with 1.5 ms, and more
// amplifies rounding on the straight groom's upright strands (a 1e-7 perturbation after 60 frames of shake: 1.1e-7 at
// 0.3, 3.8e-7 at 0.5 with 1.5e-6 on the way, 1.4e-5 at 0.7, 1.4e-4 at 1; tressvk_accuracy_probe perturb).
// (kConservativeDampingScale: planner.hpp.)
double conservative_bend_alpha(double s_step, double edge, double strand_length, double h) {
  const double rel = kCalibrationSegments * edge / strand_length;
  return kConservativeCalibration * compliant_bend_alpha_base(s_step, h) * (rel * rel * rel * rel);
}

// Local shape's damping gamma = tau / h of one edge: the time at the calibration edge (planner.cpp, kBendDampingTime)
// times min((31 a / L)^-2, kBendDampingGrowthCap); lanes_compliant.glsl alike.
constexpr double kBendDampingGrowthCap = 4.0;
double compliant_bend_damping_edge(double edge, double strand_length, double h) {
  const double rel = kCalibrationSegments * edge / strand_length;
  return compliant_bend_damping(h) * std::min(1.0 / (rel * rel), kBendDampingGrowthCap);
}
}  // namespace

void Simulator::integrate(const Substep& st) {
  const size_t count = rest_.rest_pos.size();
  const uint32_t n = rest_.vertices_per_strand;
  for (size_t i = 0; i < count; ++i) {
    const Vec3 goal = skinned_rest(st, i);
    const double w = rest_.inv_mass[i];
    if (st.reset) {
      pos_[i] = prev_[i] = prevprev_[i] = goal;
      continue;
    }
    Vec3 p = pos_[i], q = prev_[i], r = prevprev_[i];
    if (st.move_state) {
      // With a turn, p carried as a point and the history as turned differences (see integrate.comp).
      if (static_cast<float>(st.teleport.x) == 0.0f && static_cast<float>(st.teleport.y) == 0.0f &&
          static_cast<float>(st.teleport.z) == 0.0f) {
        p = p - st.origin_shift;
        q = q - st.origin_shift;
        r = r - st.origin_shift;
      } else {
        const Vec3 pq = quat_rotate(st.teleport, p - q);
        const Vec3 qr = quat_rotate(st.teleport, q - r);
        p = quat_rotate(st.teleport, p - st.origin_shift);
        q = p - pq;
        r = q - qr;
      }
    }
    Vec3 next;
    if (w > 0.0) {
      const GroupStep& gp = group_of(static_cast<uint32_t>(i / n));
      next = p + gp.velocity_keep * (p - q) + st.gravity_h2;
      // The range test is a static decision; made on the float values the GPU compares, so both agree.
      if (gp.global_stiffness > 0.0 &&
          static_cast<float>(rest_.arc_fraction[i]) <= static_cast<float>(gp.global_range)) {
        next += (compliant_model() ? compliant_global_fraction(gp.global_stiffness, st.h)
                                                          : gp.global_stiffness) *
                (goal - next);
      }
    } else {
      next = goal;
    }
    prevprev_[i] = q;
    prev_[i] = p;
    pos_[i] = next;
  }
}

void Simulator::vsp(const Substep& st) {
  const uint32_t n = rest_.vertices_per_strand;
  for (uint32_t g = 0; g < rest_.guide_count; ++g) {
    const GroupStep& gp = group_of(g);
    if (!(gp.vsp_coefficient > 0.0)) continue;
    const size_t b = size_t{g} * n;
    // The root's rigid motion needs a pinned root; the acceleration is measured at the last pinned root vertex,
    // vertex 1 when two or more are pinned (GLSL twin: vsp.comp). Every vertex reads only pinned vertices of the
    // strand, which nothing writes, so the order does not matter.
    if (!(rest_.inv_mass[b] == 0.0)) continue;
    const size_t a = rest_.inv_mass[b + 1] == 0.0 ? b + 1 : b;
    const Vec3 p0 = pos_[b], p1 = pos_[a], q0 = prev_[b], q1 = prev_[a], r0 = prevprev_[b], r1 = prevprev_[a];
    const double accel = length((p1 - q1) - (q1 - r1));
    const double ramp = std::clamp((accel - 0.75 * gp.vsp_threshold) / (0.25 * gp.vsp_threshold), 0.0, 1.0);
    const double c = gp.vsp_coefficient + ramp * (1.0 - gp.vsp_coefficient);
    // The root's skinning rotation of this step (see vsp.comp).
    const Quat swing = skin_delta(st, g);
    const Quat swing_before = skin_delta_before(st, g);
    const Vec3 t = p0 - q0, t_before = q0 - r0;
    for (uint32_t v = 1; v < n; ++v) {
      const size_t i = b + v;
      if (!(rest_.inv_mass[i] > 0.0)) continue;
      // See vsp.comp: this step's rigid motion at the vertex's start-of-step position, less the previous step's
      // rigid motion that integrate already carried (damped) as velocity.
      const Vec3 now = t + quat_rotate_delta(swing, prev_[i] - q0);
      const Vec3 before = t_before + quat_rotate_delta(swing_before, prevprev_[i] - r0);
      pos_[i] = pos_[i] + c * (now - gp.velocity_keep * before);
    }
  }
}

void Simulator::local_shape(const Substep& st) {
  const uint32_t n = rest_.vertices_per_strand;
  for (uint32_t g = 0; g < rest_.guide_count; ++g) {
    const GroupStep& gp = group_of(g);
    const double s = gp.local_stiffness;
    const size_t b = size_t{g} * n;
    const Quat root = quat_mul(skin_rotation(st, g), rest_.root_frame[g]);
    for (uint32_t it = 0; it < gp.local_iterations; ++it) {
      Quat f = root;
      for (uint32_t v = 1; v + 1 < n; ++v) {
        if (rest_.frame_turns[b + v]) {
          f = frame_align(f, pos_[b + v] - pos_[b + v - 1], rest_.rest_length[b + v - 1]);
        }
        const Vec3 target = pos_[b + v] + quat_rotate(f, rest_.rest_edge_local[b + v]);
        const Vec3 d = s * (target - pos_[b + v + 1]);
        if (rest_.inv_mass[b + v] > 0.0) pos_[b + v] -= d;
        if (rest_.inv_mass[b + v + 1] > 0.0) pos_[b + v + 1] += d;
      }
    }
  }
}

namespace {
Vec3 constraint_direction(Vec3 d, Vec3 was, double rest);
}  // namespace

// A vertex's weight in kConservative's local shape solve: 0 pinned, 1 free, 1 / (1 + k h^2) where the global spring
// pulls it (the spring's pull in integrate, a fraction f = k h^2 / (1 + k h^2) of the way to the skinned rest pose,
// and the shape solve with these weights are then one implicit step: 1 - f).
double Simulator::shape_weight(size_t i, const GroupStep& gp, double h) const {
  if (!(rest_.inv_mass[i] > 0.0)) return 0.0;
  if (gp.global_stiffness > 0.0 && static_cast<float>(rest_.arc_fraction[i]) <= static_cast<float>(gp.global_range))
    return 1.0 - compliant_global_fraction(gp.global_stiffness, h);
  return 1.0;
}

// kCompliant's and kConservative's shape targets at the current positions: every edge's direction (frame_dir_,
// constraint_direction) and every constraint's target (targets_[v], v = 1 .. n-2): edge v's skinned rest edge turned
// by the minimal rotation of the last edge before it that turns the frame (frame_turns; none: no turn), from that
// edge's skinned rest direction onto its current one. frame_edge (optional): that edge per constraint (-1: none).
void Simulator::shape_targets(size_t b, const Quat& skin, std::vector<int>* frame_edge) {
  const uint32_t n = rest_.vertices_per_strand;
  auto rest_edge = [&](uint32_t k) { return quat_rotate(skin, rest_.rest_pos[b + k + 1] - rest_.rest_pos[b + k]); };
  for (uint32_t k = 0; k + 1 < n; ++k) {
    frame_dir_[k] = constraint_direction(pos_[b + k + 1] - pos_[b + k], prev_[b + k + 1] - prev_[b + k],
                                         rest_.rest_length[b + k]);
  }
  Quat turn{0, 0, 0, 1};
  int j = -1;
  for (uint32_t v = 1; v + 1 < n; ++v) {
    const uint32_t k = v - 1;  // the edge arriving at v
    if (rest_.frame_turns[b + v] && dot(frame_dir_[k], frame_dir_[k]) > 0.0) {
      turn = quat_from_two_unit(normalize(rest_edge(k)), frame_dir_[k]);
      j = static_cast<int>(k);
    }
    targets_[v] = quat_rotate(turn, rest_edge(v));
    if (frame_edge) (*frame_edge)[v] = j;
  }
}

void Simulator::local_shape_compliant(const Substep& st) {
  // SimModel::kCompliant's local shape (see simulator.hpp). Per iteration:
  //  1. every edge's direction u_k from the current positions (blended with its previous-step direction when short
  //     or folded: constraint_direction) and every constraint's target: edge v's skinned rest edge turned by the
  //     minimal rotation that takes the skinned rest direction of the edge before it (the last one that turns the
  //     frame: frame_turns; none: no turn) onto that edge's current direction, T_v = R(ubar_j -> u_j) ebar_v. A local
  //     frame: the target depends on one edge before it, not on the whole strand's path (a frame transported along the
  //     current edges, TressFX's, gives each target a twist that depends on every edge before it, a follower load
  //     whose missing reactions made curved strands flutter; docs/accuracy.md, "Rounding amplification");
  //  2. the constraints C_v = x_{v+1} - x_v - T_v (v = 1 .. n-2) solved together with the targets held:
  //     (D W D^T + at) dlambda = -(C + at lambda), a scalar tridiagonal system with three right-hand sides (row v:
  //     (w_v + w_{v+1} + at_v) on the diagonal, -w_v and -w_{v+1} beside it; Thomas here, parallel cyclic reduction
  //     over the lanes on the GPU), then x_v += w_v (dlambda_{v-1} - dlambda_v) and lambda += dlambda
  //     (at_v: compliant_bend_alpha; w: 1 free, 0 pinned. kConservative's weights, shape_weight, measured here too:
  //     the cantilever at 60 Hz +12.7 % -> +5.1 %, but Ratboy baked at 8 vertices, shaken at 60 Hz, then stretched
  //     by 77 % in its first frames, where the length solve starts from a violent step; not taken).
  // The solve is exact, so the iterations only refresh the targets: the static sag does not depend on them.
  const uint32_t n = rest_.vertices_per_strand;
  for (uint32_t g = 0; g < rest_.guide_count; ++g) {
    const GroupStep& gp = group_of(g);
    if (gp.local_iterations == 0 || n < 3) continue;
    const size_t b = size_t{g} * n;
    const Quat skin = skin_rotation(st, g);
    auto w = [&](uint32_t v) { return rest_.inv_mass[b + v] > 0.0 ? 1.0 : 0.0; };
    for (uint32_t v = 0; v < n; ++v) lam3_[v] = Vec3{};
    for (uint32_t it = 0; it < gp.local_iterations; ++it) {
      // 1. Directions (frame_dir_), then every constraint's target (targets_).
      shape_targets(b, skin);
      // 2. The tridiagonal solve (rows v = 1 .. n-2; c' in seg_cp_, d' in tdp_).
      double cp_before = 0.0;
      Vec3 dp_before{};
      for (uint32_t v = 1; v + 1 < n; ++v) {
        const double wa = w(v), wb = w(v + 1);
        if (wa + wb == 0.0) {
          seg_cp_[v] = 0.0;
          tdp_[v] = Vec3{};
        } else {
          const double at = compliant_bend_alpha(gp.local_stiffness, rest_.rest_length[b + v], rest_.strand_length[g], st.h);
          const Vec3 c = pos_[b + v + 1] - pos_[b + v] - targets_[v];
          // The damping term (XPBD): gamma on the edge's change over the step, (1 + gamma) on D W D^T.
          const double gm = compliant_bend_damping_edge(rest_.rest_length[b + v], rest_.strand_length[g], st.h);
          const Vec3 vel = (pos_[b + v + 1] - prev_[b + v + 1]) - (pos_[b + v] - prev_[b + v]);
          const double sub = v > 1 ? -(1.0 + gm) * wa : 0.0;
          const double sup = v + 2 < n ? -(1.0 + gm) * wb : 0.0;
          const double den = (1.0 + gm) * (wa + wb) + at - sub * cp_before;
          seg_cp_[v] = sup / den;
          tdp_[v] = (-1.0 * (c + at * lam3_[v] + gm * vel) - sub * dp_before) / den;
        }
        cp_before = seg_cp_[v];
        dp_before = tdp_[v];
      }
      for (uint32_t v = n - 2; v-- > 1;) tdp_[v] -= seg_cp_[v] * tdp_[v + 1];
      for (uint32_t v = 1; v < n; ++v) {
        const Vec3 before = v >= 2 ? tdp_[v - 1] : Vec3{};
        const Vec3 here = v + 1 < n ? tdp_[v] : Vec3{};
        if (w(v) > 0.0) pos_[b + v] += before - here;
      }
      for (uint32_t v = 1; v + 1 < n; ++v) lam3_[v] += tdp_[v];
    }
  }
}

void Simulator::local_shape_conservative(const Substep& st) {
  // LengthModel::kConservative's local shape (see simulator.hpp). Per iteration: the targets as kCompliant's
  // (local_shape_compliant), each constraint's gradient blocks (I on x_{v+1}, -I on x_v, -J on x_{j+1}, +J on x_j),
  // then the symmetric system (rows divided by 1 + gamma): (G W G^T + at / (1 + gamma)) dlambda =
  // -(C + at lambda + gamma G (x - prev - carried)) / (1 + gamma), solved by a banded Cholesky factorisation
  // (constraints u and v are coupled when they share a free vertex: |u - v| <= 2 for frames that turn at every edge),
  // then x += W G^T dlambda.
  const uint32_t n = rest_.vertices_per_strand;
  if (n < 3) return;
  const uint32_t m = n - 2;  // constraints v = 1 .. n - 2, row block v - 1
  const size_t dim = size_t{3} * m;
  struct Block {
    uint32_t vertex;
    double a[9];  // row-major 3x3
  };
  std::vector<std::array<Block, 4>> grad(n);
  std::vector<uint32_t> grad_count(n, 0);
  std::vector<int> frame_edge(n, -1);
  std::vector<Vec3> lam(n), dlam(n);
  for (uint32_t g = 0; g < rest_.guide_count; ++g) {
    const GroupStep& gp = group_of(g);
    if (gp.local_iterations == 0) continue;
    const size_t b = size_t{g} * n;
    const Quat skin = skin_rotation(st, g);
    auto w = [&](uint32_t v) { return shape_weight(b + v, gp, st.h); };
    for (uint32_t v = 0; v < n; ++v) lam[v] = Vec3{};
    // What the head's rotation of this step carries each vertex by (about any point: the constraints do not see a
    // translation), taken out of the damped rate: the targets turn with the head, so a strand turning with it keeps
    // its constraints satisfied and is not damped (the rate G (x - prev) alone is their change less the targets'
    // turn; it damped a strand carried rigidly with the head by 0.012 of its length over 30 frames of `shake`).
    const Quat swing = skin_delta(st, g);
    for (uint32_t v = 0; v < n; ++v) carried_[v] = quat_rotate_delta(swing, prev_[b + v] - prev_[b]);
    for (uint32_t it = 0; it < gp.local_iterations; ++it) {
      // 1. Directions and targets (as local_shape_compliant), and each constraint's gradient blocks.
      shape_targets(b, skin, &frame_edge);
      for (uint32_t v = 1; v + 1 < n; ++v) {
        const int j = frame_edge[v];
        std::array<Block, 4>& gb = grad[v];
        gb[0] = {v + 1, {1, 0, 0, 0, 1, 0, 0, 0, 1}};
        gb[1] = {v, {-1, 0, 0, 0, -1, 0, 0, 0, -1}};
        grad_count[v] = 2;
        // The reaction is taken where the frame edge is the edge just before (everywhere on an evenly spaced strand;
        // a frame carried over a short edge keeps its target held, as kCompliant): the system stays pentadiagonal,
        // as the GPU solves it.
        if (j >= 0 && static_cast<uint32_t>(j) + 1 == v) {
          // dT/de = ((T.u) I - u T^T) / |e| (|e| at least half its rest length: a compressed edge's direction is
          // blended, constraint_direction).
          const Vec3 u = frame_dir_[j], t = targets_[v];
          const double len = std::max(length(pos_[b + j + 1] - pos_[b + j]), 0.5 * rest_.rest_length[b + j]);
          const double tu = dot(t, u);
          Block up{static_cast<uint32_t>(j + 1), {}}, lo{static_cast<uint32_t>(j), {}};
          for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) {
              const double jrc = ((r == c ? tu : 0.0) - (&u.x)[r] * (&t.x)[c]) / len;
              up.a[r * 3 + c] = -jrc;
              lo.a[r * 3 + c] = jrc;
            }
          gb[2] = up;
          gb[3] = lo;
          grad_count[v] = 4;
        }
      }
      // 2. The banded system: constraints u and v share a free vertex where |u - v| <= 2 (half bandwidth 8).
      const uint32_t reach = 1;
      const size_t p = 3 * size_t{std::min(reach + 1, m - 1)} + 2;  // |u - v| <= reach + 1
      band_.assign(dim * (p + 1), 0.0);
      band_rhs_.assign(dim, 0.0);
      auto at_band = [&](size_t r, size_t c) -> double& { return band_[r * (p + 1) + (r - c)]; };  // c <= r
      for (uint32_t v = 1; v + 1 < n; ++v) {
        const size_t rv = 3 * size_t{v - 1};
        const double at = conservative_bend_alpha(gp.local_stiffness, rest_.rest_length[b + v], rest_.strand_length[g], st.h);
        const double gm = kConservativeDampingScale * compliant_bend_damping_edge(rest_.rest_length[b + v], rest_.strand_length[g], st.h);
        bool free_vertex = false;
        for (uint32_t k = 0; k < grad_count[v]; ++k) free_vertex = free_vertex || w(grad[v][k].vertex) > 0.0;
        if (!free_vertex || !std::isfinite(at)) {
          for (int i = 0; i < 3; ++i) at_band(rv + i, rv + i) = 1.0;  // dlambda 0
          continue;
        }
        Vec3 rate{};  // G (x - prev - carried)
        for (uint32_t k = 0; k < grad_count[v]; ++k) {
          const Block& bl = grad[v][k];
          const Vec3 d = pos_[b + bl.vertex] - prev_[b + bl.vertex] - carried_[bl.vertex];
          for (int r = 0; r < 3; ++r) (&rate.x)[r] += bl.a[r * 3] * d.x + bl.a[r * 3 + 1] * d.y + bl.a[r * 3 + 2] * d.z;
        }
        const Vec3 c = pos_[b + v + 1] - pos_[b + v] - targets_[v];
        const Vec3 rhs = (-1.0 / (1.0 + gm)) * (c + at * lam[v] + gm * rate);
        for (int r = 0; r < 3; ++r) band_rhs_[rv + r] = (&rhs.x)[r];
        for (int r = 0; r < 3; ++r) at_band(rv + r, rv + r) += at / (1.0 + gm);
        // G_v W G_u^T for u <= v (the lower triangle), over the free vertices they share.
        const uint32_t u_first = v > reach + 1 ? v - reach - 1 : 1;
        for (uint32_t u = u_first; u <= v; ++u) {
          const size_t ru = 3 * size_t{u - 1};
          bool u_free = false;
          for (uint32_t k = 0; k < grad_count[u]; ++k) u_free = u_free || w(grad[u][k].vertex) > 0.0;
          if (!u_free || !std::isfinite(conservative_bend_alpha(gp.local_stiffness, rest_.rest_length[b + u],
                                                                rest_.strand_length[g], st.h)))
            continue;
          for (uint32_t kv = 0; kv < grad_count[v]; ++kv)
            for (uint32_t ku = 0; ku < grad_count[u]; ++ku) {
              const Block& x = grad[v][kv];
              const Block& y = grad[u][ku];
              if (x.vertex != y.vertex || w(x.vertex) == 0.0) continue;
              const double wx = w(x.vertex);
              for (int r = 0; r < 3; ++r)
                for (int c2 = 0; c2 < 3; ++c2) {
                  if (u == v && c2 > r) continue;
                  double sum = 0.0;
                  for (int l = 0; l < 3; ++l) sum += x.a[r * 3 + l] * y.a[c2 * 3 + l];
                  at_band(rv + r, ru + c2) += wx * sum;
                }
            }
        }
      }
      // 3. Cholesky (L L^T, in place in the band), forward and back substitution.
      for (size_t r = 0; r < dim; ++r) {
        const size_t c0 = r > p ? r - p : 0;
        for (size_t c = c0; c <= r; ++c) {
          double sum = at_band(r, c);
          const size_t k0 = std::max(c0, c > p ? c - p : 0);
          for (size_t k = k0; k < c; ++k) sum -= at_band(r, k) * at_band(c, k);
          if (c < r) {
            at_band(r, c) = sum / at_band(c, c);
          } else {
            at_band(r, r) = std::sqrt(std::max(sum, 1e-300));
          }
        }
      }
      for (size_t r = 0; r < dim; ++r) {
        double sum = band_rhs_[r];
        for (size_t k = r > p ? r - p : 0; k < r; ++k) sum -= at_band(r, k) * band_rhs_[k];
        band_rhs_[r] = sum / at_band(r, r);
      }
      for (size_t r = dim; r-- > 0;) {
        double sum = band_rhs_[r];
        for (size_t k = r + 1; k < std::min(dim, r + p + 1); ++k) sum -= at_band(k, r) * band_rhs_[k];
        band_rhs_[r] = sum / at_band(r, r);
      }
      // 4. x += W G^T dlambda; lambda += dlambda.
      for (uint32_t v = 1; v + 1 < n; ++v) {
        dlam[v] = Vec3{band_rhs_[3 * (v - 1)], band_rhs_[3 * (v - 1) + 1], band_rhs_[3 * (v - 1) + 2]};
        lam[v] += dlam[v];
      }
      for (uint32_t v = 1; v + 1 < n; ++v) {
        for (uint32_t k = 0; k < grad_count[v]; ++k) {
          const Block& bl = grad[v][k];
          if (w(bl.vertex) == 0.0) continue;
          const Vec3 d = w(bl.vertex) * dlam[v];
          // G^T: the block's transpose.
          pos_[b + bl.vertex] += Vec3{bl.a[0] * d.x + bl.a[3] * d.y + bl.a[6] * d.z,
                                      bl.a[1] * d.x + bl.a[4] * d.y + bl.a[7] * d.z,
                                      bl.a[2] * d.x + bl.a[5] * d.y + bl.a[8] * d.z};
        }
      }
    }
  }
}

namespace {
// The (unnormalised) direction a length constraint restores along: the segment d itself, except that a compressed or
// flipped segment is blended with its direction at the previous step (was) by the missing length (and the fold
// guard), which stays defined as the segment vanishes (normalize(d) would not). GLSL twin: length.comp.
Vec3 blended_direction(Vec3 d, Vec3 was, double rest) {
  const double len = length(d);
  Vec3 dir = d;
  const double wl = length(was);
  if (wl > kDirectionEps * rest) {
    const Vec3 u = was / wl;
    const double blend = std::max(kCollapse * rest - len, 0.0) + fold_guard(d, len, u);
    if (blend > 0.0) dir = d + blend * u;
  }
  return dir;
}
// The same as a unit vector; zero when no direction is defined.
Vec3 constraint_direction(Vec3 d, Vec3 was, double rest) {
  const Vec3 dir = blended_direction(d, was, rest);
  const double dl = length(dir);
  return dl > 0.0 ? dir / dl : Vec3{};
}
}  // namespace

void Simulator::solve_lengths(size_t b, double weight) {
  // One Newton step of C_v(x) = |x_{v+1} - x_v| - rest_v = 0 for every segment at once. The correction moves each free
  // vertex along the segments' directions midway between the start of the step and now (m_v; the implicit midpoint
  // rule, which dissipates nothing), by multipliers lambda from the tridiagonal system
  //   (W_v + W_{v+1}) (g_v . m_v) lambda_v - W_v (g_v . m_{v-1}) lambda_{v-1} - W_{v+1} (g_v . m_{v+1}) lambda_{v+1}
  //     = C_v,
  // g_v the constraint gradient now, W 1 for a free vertex and 0 for a pinned one (Thomas algorithm; a row of two
  // pinned vertices is lambda_v = 0). Then x_v += lambda_v m_v - lambda_{v-1} m_{v-1}. GLSL twin: solve_lengths in
  // length.comp (solve_tip_pinned; the Newmark model has no GPU twin yet).
  const uint32_t n = rest_.vertices_per_strand, m = n - 1;
  auto w = [&](uint32_t v) { return rest_.inv_mass[b + v] > 0.0 ? 1.0 : 0.0; };
  auto mid_dir = [&](uint32_t v, Vec3 g) {
    const Vec3 d = pos_[b + v + 1] - pos_[b + v];
    const Vec3 was = prev_[b + v + 1] - prev_[b + v];
    // The Newmark model moves along the gradient (a projection; implicit_transverse then moves the transverse
    // response to the average-acceleration rule); the follow-the-leader model's tip-pinned solve along the direction
    // midway between the start of the step and now.
    if (length_model_ != LengthModel::kFollowTheLeader) return g;
    const Vec3 mid = constraint_direction(0.5 * (d + was), was, rest_.rest_length[b + v]);
    return dot(g, mid) > 0.5 ? mid : g;
  };
  auto grad = [&](uint32_t v) {
    return constraint_direction(pos_[b + v + 1] - pos_[b + v], prev_[b + v + 1] - prev_[b + v], rest_.rest_length[b + v]);
  };
  Vec3 g_here = grad(0), m_before{}, m_here = mid_dir(0, g_here);
  double cp_before = 0.0, dp_before = 0.0;
  for (uint32_t v = 0; v < m; ++v) {
    Vec3 g_next{}, m_next{};
    if (v + 1 < m) {
      g_next = grad(v + 1);
      m_next = mid_dir(v + 1, g_next);
    }
    const double wa = w(v), wb = w(v + 1);
    // A segment with no defined direction (g = 0: vanished, with no history) has no row: lambda = 0.
    const bool active = wa + wb > 0.0 && (length_model_ == LengthModel::kFollowTheLeader || dot(g_here, m_here) > 0.25);
    const double diag = active ? (wa + wb) * dot(g_here, m_here) : 1.0;
    const double c = active ? dot(pos_[b + v + 1] - pos_[b + v], g_here) - rest_.rest_length[b + v] : 0.0;
    const double sub = active && v > 0 ? -wa * dot(g_here, m_before) : 0.0;
    const double sup = active && v + 1 < m ? -wb * dot(g_here, m_next) : 0.0;
    const double den = std::max(diag - sub * cp_before, kSolvePivotMin * diag);
    seg_cp_[v] = sup / den;
    seg_dp_[v] = (c - sub * dp_before) / den;
    cp_before = seg_cp_[v];
    dp_before = seg_dp_[v];
    m_before = m_here;
    g_here = g_next;
    m_here = m_next;
  }
  for (uint32_t v = m - 1; v-- > 0;) seg_dp_[v] -= seg_cp_[v] * seg_dp_[v + 1];  // now lambda
  // A damped Newton step: when the linearisation asks a vertex to move more than half of its shorter segment (large
  // steps, violent motion), the whole update is scaled down to that, so the iteration cannot diverge; the clean-up
  // sweep then restores the lengths. The scale is 1 in ordinary motion.
  auto move_of = [&](uint32_t v, Vec3 m_v, Vec3 m_prev) {
    Vec3 dx{};
    if (v < m) dx += seg_dp_[v] * m_v;
    if (v > 0) dx -= seg_dp_[v - 1] * m_prev;
    return dx;
  };
  // SimModel::kCompliant measures the reach against segments of at least half the strand's mean segment: a
  // sub-micrometre segment (hard case 8) would otherwise hold every Newton step of its strand to a fraction of a
  // micrometre, and the strand's other segments stayed stretched by up to 75 %; its direction stays defined as it
  // vanishes (constraint_direction).
  const double reach_floor = compliant_model()
                                 ? kCompliantReachFloorRel * rest_.strand_length[b / n] / static_cast<double>(m)
                                 : 0.0;
  double scale = weight;
  Vec3 m_prev{};
  for (uint32_t v = 0; v < n; ++v) {
    const Vec3 m_v = v < m ? mid_dir(v, grad(v)) : Vec3{};
    if (w(v) > 0.0) {
      const double reach = 0.5 * std::min(v > 0 ? std::max(rest_.rest_length[b + v - 1], reach_floor) : INFINITY,
                                          v < m ? std::max(rest_.rest_length[b + v], reach_floor) : INFINITY);
      const double len = length(move_of(v, m_v, m_prev));
      if (len * scale > reach) scale = reach / len;
    }
    m_prev = m_v;
  }
  m_prev = Vec3{};
  for (uint32_t v = 0; v < n; ++v) {
    const Vec3 m_v = v < m ? mid_dir(v, grad(v)) : Vec3{};  // from positions not yet moved (v and v + 1)
    if (w(v) > 0.0) {
      const Vec3 dx = scale * move_of(v, m_v, m_prev);
      pos_[b + v] += dx;
      move_[v] += dx;
    }
    m_prev = m_v;
  }
  for (uint32_t v = 0; v < m; ++v) lam_[v] += scale * seg_dp_[v];  // for implicit_transverse (Newmark model)
}

void Simulator::implicit_transverse(size_t b, double alpha) {
  // The Newton steps moved the strand from its predicted state x~ to x1 by move_ (the constraint forces, h^2 T along
  // the segments) with the directions of x~: explicit in the strand's transverse motion, whose stiffness is the
  // tension over the segment length (A u_v = sum over the segments s at v of (lam_s / rest_s) (u_v - u_other), per
  // unit mass and h^2). Explicit is stable only while h sqrt(4 T / rest) < 2, which a long, finely divided or short
  // strand at a low step rate is not (a hanging 32-vertex 0.3 m chain at 120 Hz, 64 vertices at 240 Hz). This moves
  // the force to the average-acceleration (Newmark beta 1/4) state, x* = x~ - A (x*/4 + x_n/2 + x_{n-1}/4) + ...:
  //   (I + alpha A) delta = -A (x1/4 + x_n/2 + x_{n-1}/4 - x~),  alpha = 1/4,
  // a tridiagonal solve per coordinate (pinned vertices: delta = 0; compression: no stiffness). Unconditionally
  // stable and without numerical dissipation in the linear regime; the follow-the-leader clean-up after it restores
  // the lengths (the longitudinal part of delta is second order).
  const uint32_t n = rest_.vertices_per_strand, m = n - 1;
  auto k = [&](uint32_t seg) { return alpha * std::max(lam_[seg], 0.0) / rest_.rest_length[b + seg]; };
  auto free_v = [&](uint32_t v) { return rest_.inv_mass[b + v] > 0.0; };
  // Row v: -k_{v-1} delta_{v-1} + (1 + k_{v-1} + k_v) delta_v - k_v delta_{v+1} = -(alpha A move)_v.
  double cp_before = 0.0;
  Vec3 dp_before{};
  for (uint32_t v = 0; v < n; ++v) {
    const double kl = v > 0 ? k(v - 1) : 0.0, kr = v < m ? k(v) : 0.0;
    if (!free_v(v)) {
      seg_cp_[v] = 0.0;
      tdp_[v] = Vec3{};
    } else {
      Vec3 rhs{};
      auto c = [&](uint32_t u) {  // (the state the force should see - the predicted state it saw) / alpha
        const Vec3 x1 = pos_[b + u], xt = x1 - move_[u];
        return (1.0 / alpha) * (0.25 * x1 + 0.5 * prev_[b + u] + 0.25 * prevprev_[b + u] - xt);
      };
      if (v > 0) rhs -= kl * (c(v) - c(v - 1));
      if (v < m) rhs -= kr * (c(v) - c(v + 1));
      const double sub = v > 0 && free_v(v - 1) ? -kl : 0.0;
      const double sup = v < m && free_v(v + 1) ? -kr : 0.0;
      const double den = 1.0 + kl + kr - sub * cp_before;
      seg_cp_[v] = sup / den;
      tdp_[v] = (rhs - sub * dp_before) / den;
    }
    cp_before = seg_cp_[v];
    dp_before = tdp_[v];
  }
  for (uint32_t v = m; v-- > 0;) tdp_[v] -= seg_cp_[v] * tdp_[v + 1];
  for (uint32_t v = 0; v < n; ++v) {
    if (free_v(v)) pos_[b + v] += tdp_[v];
  }
}

void Simulator::length_and_collision(const Substep& st) {
  const uint32_t n = rest_.vertices_per_strand;
  for (uint32_t g = 0; g < rest_.guide_count; ++g) {
    const GroupStep& gp = group_of(g);
    const size_t b = size_t{g} * n;
    auto movable = [&](size_t i) { return rest_.inv_mass[i] > 0.0; };

    if (st.wind) {
      const double a = static_cast<double>(g % 20u) / 20.0;
      const Vec3 w = a * (st.wind_h2[0] + st.wind_h2[2]) + (1.0 - a) * (st.wind_h2[1] + st.wind_h2[3]);
      // The compliant model walks from the tip, so that every segment's direction is the one before the wind (the
      // lanes of its GPU kernel push all vertices at once); the other models from the root, each parent pushed.
      const bool from_tip = compliant_model();
      for (uint32_t k = 1; k < n; ++k) {
        const uint32_t v = from_tip ? n - k : k;
        if (!movable(b + v)) continue;
        const Vec3 e = pos_[b + v] - pos_[b + v - 1];
        const double len = length(e);
        Vec3 push = w;
        if (len > kDirectionEps * rest_.rest_length[b + v - 1]) {
          const Vec3 t = e / len;
          push = w - dot(w, t) * t;
        }
        pos_[b + v] += push;
      }
    }

    for (uint32_t v = 0; v < n && st.capsule_count > 0; ++v) {
      const size_t i = b + v;
      if (!movable(i)) continue;
      Vec3 x = pos_[i], y = prev_[i];
      bool hit = false;
      for (uint32_t c = 0; c < st.capsule_count; ++c) {
        const CapsuleSim& cap = st.capsules[c];
        const Vec3 axis = cap.p1 - cap.p0;
        const double aa = dot(axis, axis);
        const double t = aa > 0.0 ? std::clamp(dot(x - cap.p0, axis) / aa, 0.0, 1.0) : 0.0;
        const Vec3 centre = cap.p0 + t * axis;
        const double radius = cap.r0 + t * (cap.r1 - cap.r0);
        const Vec3 d = x - centre;
        const double dist = length(d);
        if (!(dist < radius)) continue;
        Vec3 nrm;
        if (dist > kDirectionEps * radius) {
          nrm = d / dist;
        } else {
          const Vec3 back = y - centre;
          const double bl = length(back);
          nrm = bl > kDirectionEps * radius ? back / bl : Vec3{0, 1, 0};
        }
        const double depth = radius - dist;
        x = centre + radius * nrm;
        const double vn = dot((x - y) - (cap.m0 + t * (cap.m1 - cap.m0)), nrm);
        if (vn < 0.0) y += std::min(depth / (kContactBand * radius), 1.0) * vn * nrm;
        hit = true;
      }
      if (hit) {
        pos_[i] = x;
        prev_[i] = y;
      }
    }

    // One segment's length constraint with end weights wa (root-ward) and wb (tip-ward), moving the ends along the
    // segment's direction (blended with the previous step's when compressed or flipped: constraint_direction). dftl:
    // a follow-the-leader move of the child, whose parent gets the opposite of the move as velocity (the DFTL
    // correction, which keeps the strand's momentum plausible and removes FTL's energy gain).
    auto segment = [&](uint32_t v, double wa, double wb, bool dftl) {
      const double wsum = wa + wb;
      if (wsum == 0.0) return;
      const Vec3 d = pos_[b + v + 1] - pos_[b + v];
      const double rest = rest_.rest_length[b + v];
      const Vec3 dir = blended_direction(d, prev_[b + v + 1] - prev_[b + v], rest);
      const double dl = length(dir);
      if (!(dl > 0.0)) return;
      const Vec3 corr = (d - (rest / dl) * dir) / wsum;
      if (wa > 0.0) pos_[b + v] += wa * corr;
      if (wb > 0.0) pos_[b + v + 1] -= wb * corr;
      if (dftl && wa == 0.0 && wb > 0.0 && movable(b + v)) prev_[b + v] -= kFtlVelocityCorrection * corr;
    };
    // A positions-only follow-the-leader clean-up of a strand pinned at both ends, from both ends toward its middle
    // segment (from the root alone the whole error would stay next to the pinned tip).
    const auto clean_up_from_both_ends = [&] {
      const uint32_t split = (n - 1) / 2;
      for (uint32_t v = 0; v < split; ++v) {
        const double wb = movable(b + v + 1) ? 1.0 : 0.0;
        segment(v, (movable(b + v) && !(wb > 0.0)) ? 1.0 : 0.0, wb, false);
      }
      for (uint32_t v = n - 2; v > split; --v) {
        const double wa = movable(b + v) ? 1.0 : 0.0;
        segment(v, wa, (movable(b + v + 1) && !(wa > 0.0)) ? 1.0 : 0.0, false);
      }
      segment(split, movable(b + split) ? 1.0 : 0.0, movable(b + split + 1) ? 1.0 : 0.0, false);
    };
    if (compliant_model()) {
      // SimModel::kCompliant: the Newmark model's Newton step and implicit transverse response, then
      // length_iterations more Newton steps (projections of what the transverse solve moved); every step a tridiagonal solve over the strand (parallel cyclic
      // reduction over the lanes on the GPU), and no serial clean-up: what the linearisation leaves is second order in
      // the step's move and the next step's solve starts from it.
      std::fill(move_.begin(), move_.end(), Vec3{});
      std::fill(lam_.begin(), lam_.end(), 0.0);
      solve_lengths(b);
      implicit_transverse(b, 0.25);
      for (uint32_t it = 0; it < gp.length_iterations; ++it) solve_lengths(b);
      // Violent motion (a damped Newton step, a whipping tip): up to kCompliantExtraNewton more steps while any
      // segment is off its length by more than kCompliantStretchTol (a reduction over the strand's lanes on the GPU).
      // Each is weighted by how far over the tolerance the worst segment is (0 at it, whole from twice it), so that
      // the step is a continuous function of the state: as a hard switch, a float state just under the tolerance
      // and its double twin just over it took different steps (1-frame differences of 3e-4 of the strand length).
      // The strand's worst segment (with a free end): how far off its rest length, relative to it.
      const auto worst_off = [&] {
        double worst = 0.0;
        for (uint32_t v = 0; v + 1 < n; ++v) {
          if (!movable(b + v) && !movable(b + v + 1)) continue;
          const double rest = rest_.rest_length[b + v];
          worst = std::max(worst, std::abs(length(pos_[b + v + 1] - pos_[b + v]) - rest) / rest);
        }
        return worst;
      };
      bool settled = false;  // within kCompliantStretchTol, so below the fallback's threshold too
      for (uint32_t extra = 0; extra < kCompliantExtraNewton; ++extra) {
        const double worst = worst_off();
        settled = !(worst > kCompliantStretchTol);
        if (settled) break;
        solve_lengths(b, std::min((worst - kCompliantStretchTol) / kCompliantStretchTol, 1.0));
      }
      // The conservative model's fallback (its recommended 1 local iteration at 120 Hz left hard case 2's strands
      // stretched by 0.41: capsule pushes larger than the damped Newton steps restore, 16 of them 0.35): where a
      // segment is still off by more than kConservativeFallbackStretch, a follow-the-leader clean-up from the root
      // (each free vertex put back at its rest length from its cleaned parent, along its own direction), its move
      // weighted from 0 there to whole at twice that, continuous in the state as the extra Newton steps are. Strands
      // with a free tip only (from the root alone a pinned tip would keep the whole error next to it).
      if (length_model_ == LengthModel::kConservative && !settled && movable(b + n - 1)) {
        const double worst = worst_off();
        const double weight =
            std::clamp((worst - kConservativeFallbackStretch) / kConservativeFallbackStretch, 0.0, 1.0);
        if (weight > 0.0) {
          Vec3 parent = pos_[b];  // the cleaned position of the vertex before
          for (uint32_t v = 1; v < n; ++v) {
            const Vec3 mine = pos_[b + v];
            Vec3 cleaned = mine;
            if (movable(b + v)) {
              const Vec3 d = mine - parent;
              const double l = length(d);
              if (l > 0.0) cleaned = parent + (rest_.rest_length[b + v - 1] / l) * d;
            }
            pos_[b + v] = mine + weight * (cleaned - mine);
            parent = cleaned;
          }
        }
      }
    } else if (length_model_ == LengthModel::kNewmark) {
      // LengthModel::kNewmark (opt-in, not yet the default: see simulator.hpp). Every strand alike:
      // a Newton step of the whole strand's constraint system (solve_lengths: a tridiagonal solve moving each vertex
      // along the constraint gradients; no velocity correction, so p - q stays the velocity), its transverse response
      // moved to the average-acceleration rule (implicit_transverse: stable at every step rate and without numerical
      // dissipation), length_iterations - 1 more Newton steps (projections of what is left), then a positions-only
      // follow-the-leader clean-up for the rest (second order in the step's move). A root-pinned (or free) strand is cleaned up from the root; one pinned at both ends
      // from both ends toward its middle segment.
      std::fill(move_.begin(), move_.end(), Vec3{});
      std::fill(lam_.begin(), lam_.end(), 0.0);
      solve_lengths(b);
      implicit_transverse(b, 0.25);
      for (uint32_t it = 1; it < gp.length_iterations; ++it) solve_lengths(b);
      if (movable(b + n - 1)) {
        for (uint32_t v = 0; v + 1 < n; ++v) {
          const double wb = movable(b + v + 1) ? 1.0 : 0.0;
          segment(v, (movable(b + v) && !(wb > 0.0)) ? 1.0 : 0.0, wb, false);
        }
      } else {
        clean_up_from_both_ends();
      }
    } else if (movable(b + n - 1)) {
      for (uint32_t it = 0; it < gp.length_iterations; ++it) {
        const bool last_sweep = it + 1 == gp.length_iterations;
        for (uint32_t v = 0; v + 1 < n; ++v) {
          const double wb = movable(b + v + 1) ? 1.0 : 0.0;
          const double wa = (movable(b + v) && !(last_sweep && wb > 0.0)) ? 1.0 : 0.0;
          segment(v, wa, wb, last_sweep);
        }
      }
    } else {
      // A strand pinned at its tip too (TressFX bothEndsImmovable): follow-the-leader from the root would leave the
      // step's whole error in the segment next to the pinned tip (335 % stretch measured on a hanging catenary), and
      // from both ends the two halves slide against their middle (170 % there). Instead length_iterations Newton
      // steps of the whole strand's constraint system (solve_lengths), then a follow-the-leader clean-up from both
      // ends toward the middle segment for what the linearisation left, which moves positions only.
      for (uint32_t it = 0; it < gp.length_iterations; ++it) solve_lengths(b);
      clean_up_from_both_ends();
    }

    if (gp.max_step > 0.0) {
      for (uint32_t v = 0; v < n; ++v) {
        const size_t i = b + v;
        if (!movable(i)) continue;
        const Vec3 stepv = pos_[i] - prev_[i];
        const double len = length(stepv);
        if (len > gp.max_step) prev_[i] = pos_[i] - stepv * (gp.max_step / len);
      }
    }

    bool ok = true;
    for (uint32_t v = 0; v < n; ++v) ok = ok && is_finite(pos_[b + v]) && is_finite(prev_[b + v]);
    if (!ok) {
      // History: the rest pose carried back by this step's rigid motion (see length.comp).
      const Vec3 p0 = skinned_rest(st, b);
      Vec3 q0 = prev_[b];
      if (!is_finite(q0)) q0 = p0;
      const Quat back = conjugate(skin_delta(st, g));
      for (uint32_t v = 0; v < n; ++v) {
        const Vec3 p = skinned_rest(st, b + v);
        const Vec3 y = q0 + quat_rotate(back, p - p0);
        pos_[b + v] = p;
        prev_[b + v] = prevprev_[b + v] = y;
      }
      ++nonfinite_resets_;
    }

    const double min_len = kDirectionEps * rest_.strand_length[g] / static_cast<double>(n - 1);
    Vec3 last = quat_rotate(current_root_frame(st, g), Vec3{1, 0, 0});
    for (uint32_t v = 0; v < n; ++v) {
      const Vec3 e = v + 1 < n ? pos_[b + v + 1] - pos_[b + v] : pos_[b + v] - pos_[b + v - 1];
      const double len = length(e);
      if (len > min_len) last = e / len;
      tangent_[b + v] = last;
    }
  }
}

void Simulator::follow(const Substep& st) {
  const uint32_t n = rest_.vertices_per_strand, k = rest_.follow_per_guide, gc = rest_.guide_count;
  for (uint32_t f = 0; f < k; ++f) {
    for (uint32_t g = 0; g < gc; ++g) {
      const GroupStep& gp = group_of(g);
      const Vec3 offset = quat_rotate(current_root_frame(st, g), rest_.follow_offset[size_t{g} * k + f]);
      for (uint32_t v = 0; v < n; ++v) {
        const double spread = 1.0 + gp.tip_separation * static_cast<double>(v) / static_cast<double>(n - 1);
        const size_t src = size_t{g} * n + v;
        const size_t dst = (size_t{f + 1} * gc + g) * n + v;
        pos_[dst] = pos_[src] + spread * offset;
        tangent_[dst] = tangent_[src];
      }
    }
  }
}

}  // namespace tressvk::reference
