// Hard case 8's groom (docs/accuracy.md, "Hard cases"), shared by `tressvk-bench hardcases` and the reference's
// tests and probes: straight strands with sub-micrometre segments.
#pragma once

#include <tressvk/asset.hpp>
#include <tressvk/model/math.hpp>

namespace tressvk::reference {

// The straight groom `a` (at least 3 guides of at least 11 vertices) with near-duplicate vertices: in guide 0 vertex
// 5 moved to 0.2 um after vertex 4, in guide 1 the tip to 0.2 um after vertex N-2, in guide 2 vertices 8..10 within
// 0.4 um of vertex 7 (a duplicate cluster); their rest lengths and rest edges follow. A valid asset has no exactly
// zero segment (the baker merges repeated vertices and drops zero-length strands, and the asset validator refuses a
// zero rest length), so these are the shortest segments the model can be given: about 30 float ulps at 0.1 m from
// the origin.
inline asset::HairAsset with_near_duplicate_vertices(asset::HairAsset a) {
  using model::Quat;
  using model::Vec3;
  const uint32_t n = a.vertices_per_strand;
  const auto pos = [&](size_t i) {
    const auto& p = a.rest_positions[i];
    return Vec3{p[0], p[1], p[2]};
  };
  const auto place = [&](size_t g, uint32_t v, uint32_t after, double distance) {
    const size_t b = g * n;
    const Vec3 dir = model::normalize(pos(b + n - 1) - pos(b));
    const Vec3 p = pos(b + after) + distance * dir;
    for (int k = 0; k < 3; ++k) a.rest_positions[b + v][k] = static_cast<float>(k == 0 ? p.x : k == 1 ? p.y : p.z);
  };
  place(0, 5, 4, 2e-7);
  place(1, n - 1, n - 2, 2e-7);
  place(2, 8, 7, 1e-7);
  place(2, 9, 7, 2e-7);
  place(2, 10, 7, 4e-7);
  for (size_t g = 0; g < 3; ++g)
    for (uint32_t v = 0; v + 1 < n; ++v) {
      const size_t i = g * n + v;
      const Vec3 d = pos(i + 1) - pos(i);
      a.rest_lengths[i] = static_cast<float>(model::length(d));
      const auto& q = a.rest_frames[i];
      const Quat c = model::conjugate(Quat{q[0], q[1], q[2], q[3]});  // d in the rest frame: q^-1 d q
      const Vec3 e = model::quat_mul(model::quat_mul(c, model::make_quat(d, 0.0)), model::conjugate(c)).v();
      a.rest_edge_local[i] = {static_cast<float>(e.x), static_cast<float>(e.y), static_cast<float>(e.z), 0.0f};
    }
  return a;
}

}  // namespace tressvk::reference
