// Consistency checks on an in-memory asset (used by the reader, the baker and `tressvk-bake validate`).
//
// Geometric checks compare float32 data against what it claims to be, so their tolerances come from float32
// precision relative to the magnitudes involved (segment length and distance from the origin), never from an
// absolute length in scene units.
#include <tressvk/asset_io.hpp>

#include <algorithm>
#include <cmath>
#include <set>

namespace tressvk::asset {
namespace {

using Vec3 = std::array<double, 3>;

Vec3 rotate(const std::array<float, 4>& q, const Vec3& v) {
  // v' = v + 2w(q x v) + 2 q x (q x v), for unit q = (x, y, z, w).
  const Vec3 u{q[0], q[1], q[2]};
  const double w = q[3];
  const Vec3 t{2.0 * (u[1] * v[2] - u[2] * v[1]), 2.0 * (u[2] * v[0] - u[0] * v[2]), 2.0 * (u[0] * v[1] - u[1] * v[0])};
  return {v[0] + w * t[0] + (u[1] * t[2] - u[2] * t[1]), v[1] + w * t[1] + (u[2] * t[0] - u[0] * t[2]),
          v[2] + w * t[2] + (u[0] * t[1] - u[1] * t[0])};
}

bool finite4(const std::array<float, 4>& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]) && std::isfinite(v[3]);
}

double norm(const Vec3& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// float32 has a 24-bit mantissa (relative step 6e-8); values below went through a few float operations, so a
// margin of 64 steps of the largest magnitude involved keeps the check strict yet free of false alarms.
constexpr double kFloatSlack = 64.0 * 5.96e-8;

}  // namespace

std::vector<std::string> validate(const HairAsset& a) {
  std::vector<std::string> issues;
  auto issue = [&](std::string s) {
    if (issues.size() < 20) issues.push_back(std::move(s));
  };
  const uint32_t n = a.vertices_per_strand;
  if (n < kMinVerticesPerStrand || n > kMaxVerticesPerStrand) {
    issue("vertices_per_strand " + std::to_string(n) + " outside 4..128");
    return issues;
  }
  if (a.rest_positions.empty() || a.rest_positions.size() % n != 0) {
    issue("rest_positions: " + std::to_string(a.rest_positions.size()) + " entries, not a positive multiple of " +
          std::to_string(n));
    return issues;
  }
  const size_t g = a.rest_positions.size() / n;
  const size_t vc = a.rest_positions.size();
  if (a.follow_per_guide > kMaxFollowPerGuide) {
    issue("follow_per_guide " + std::to_string(a.follow_per_guide) + " exceeds " + std::to_string(kMaxFollowPerGuide));
    return issues;
  }
  if (uint64_t{g} * (1 + a.follow_per_guide) * n > kMaxRenderedVertices) {
    issue("guides x (1 + follow_per_guide) x vertices_per_strand = " +
          std::to_string(uint64_t{g} * (1 + a.follow_per_guide) * n) + " rendered vertices exceeds the limit of " +
          std::to_string(kMaxRenderedVertices));
    return issues;
  }
  if (a.rest_lengths.size() != vc) issue("rest_lengths: size differs from rest_positions");
  if (a.rest_frames.size() != vc) issue("rest_frames: size differs from rest_positions");
  if (a.rest_edge_local.size() != vc) issue("rest_edge_local: size differs from rest_positions");
  if (a.guide_group.size() != g) issue("guide_group: " + std::to_string(a.guide_group.size()) + " entries for " +
                                       std::to_string(g) + " guides");
  if (!a.root_uv.empty() && a.root_uv.size() != g) issue("root_uv: size is neither 0 nor the guide count");
  if (!a.bone_weights.empty() && a.bone_weights.size() != g) issue("bone_weights: size is neither 0 nor the guide count");
  if (a.follow_offsets.size() != g * a.follow_per_guide)
    issue("follow_offsets: " + std::to_string(a.follow_offsets.size()) + " entries, expected guides x follow_per_guide = " +
          std::to_string(g * a.follow_per_guide));
  if (a.groups.empty()) issue("groups: an asset needs at least one group");
  if (!std::isfinite(a.tip_separation) || a.tip_separation < 0.0f) issue("tip_separation: not a finite value >= 0");
  for (double o : a.origin)
    if (!std::isfinite(o)) issue("origin: not finite");
  std::set<std::string> names;
  for (const auto& grp : a.groups)
    if (!names.insert(grp.name).second) issue("groups: duplicate name '" + grp.name + "'");
  if (!issues.empty()) return issues;

  for (size_t s = 0; s < g; ++s) {
    if (a.guide_group[s] >= a.groups.size()) issue("guide " + std::to_string(s) + ": group index out of range");
    for (uint32_t v = 0; v < n; ++v) {
      const size_t i = s * n + v;
      const std::string where = "guide " + std::to_string(s) + " vertex " + std::to_string(v) + ": ";
      const auto& p = a.rest_positions[i];
      const auto& q = a.rest_frames[i];
      const auto& e = a.rest_edge_local[i];
      if (!finite4(p) || !finite4(q) || !finite4(e) || !std::isfinite(a.rest_lengths[i])) {
        issue(where + "non-finite value");
        continue;
      }
      if (p[3] < 0.0f) issue(where + "negative inverse mass");
      const double qn = std::sqrt(double{q[0]} * q[0] + double{q[1]} * q[1] + double{q[2]} * q[2] + double{q[3]} * q[3]);
      if (std::abs(qn - 1.0) > 1e-5) issue(where + "rest frame is not a unit quaternion");
      if (v + 1 == n) {
        if (a.rest_lengths[i] != 0.0f || e[0] != 0.0f || e[1] != 0.0f || e[2] != 0.0f)
          issue(where + "last vertex must have zero rest length and rest edge");
        continue;
      }
      const auto& p1 = a.rest_positions[i + 1];
      const Vec3 d{double{p1[0]} - p[0], double{p1[1]} - p[1], double{p1[2]} - p[2]};
      const double len = norm(d);
      const double magnitude = std::max({len, norm(Vec3{p[0], p[1], p[2]}), norm(Vec3{p1[0], p1[1], p1[2]})});
      const double tol = kFloatSlack * magnitude;
      if (!(a.rest_lengths[i] > 0.0f)) issue(where + "rest length is not positive");
      if (std::abs(a.rest_lengths[i] - len) > tol) issue(where + "rest length differs from the positions");
      const Vec3 back = rotate(q, {e[0], e[1], e[2]});
      if (norm({back[0] - d[0], back[1] - d[1], back[2] - d[2]}) > tol + 1e-5 * len)
        issue(where + "rest edge in its frame does not match the positions");
    }
    if (!a.bone_weights.empty()) {
      const auto& b = a.bone_weights[s];
      double sum = 0.0;
      for (size_t k = 0; k < kMaxBoneInfluences; ++k) {
        if (!std::isfinite(b.weight[k]) || b.weight[k] < 0.0f) issue("guide " + std::to_string(s) + ": bad bone weight");
        if (k > 0 && b.weight[k] > b.weight[k - 1]) issue("guide " + std::to_string(s) + ": bone weights not sorted");
        if (b.weight[k] > 0.0f && b.bone[k] >= a.bone_names.size())
          issue("guide " + std::to_string(s) + ": bone index out of range");
        sum += b.weight[k];
      }
      if (std::abs(sum - 1.0) > 1e-5) issue("guide " + std::to_string(s) + ": bone weights do not sum to 1");
    }
    if (issues.size() >= 20) break;
  }
  for (size_t f = 0; f < a.follow_offsets.size(); ++f)
    if (!finite4(a.follow_offsets[f])) issue("follow " + std::to_string(f) + ": non-finite offset");
  return issues;
}

Bounds guide_bounds(const HairAsset& a) {
  Bounds b;
  if (a.rest_positions.empty()) return b;
  b.min = {1e300, 1e300, 1e300};
  b.max = {-1e300, -1e300, -1e300};
  for (const auto& p : a.rest_positions)
    for (size_t k = 0; k < 3; ++k) {
      b.min[k] = std::min(b.min[k], a.origin[k] + p[k]);
      b.max[k] = std::max(b.max[k], a.origin[k] + p[k]);
    }
  return b;
}

}  // namespace tressvk::asset
