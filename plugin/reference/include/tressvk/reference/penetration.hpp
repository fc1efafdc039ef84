// The penetration metric (docs/accuracy.md): how deep free guide vertices end a frame inside the frame's capsules,
// relative to the capsule's radius there, and the fastest speed of a vertex in the frame after it touched a capsule,
// relative to the capsule's surface (a deep contact that the solver resolves by ejecting the vertex shows up as that
// speed). Fed frame by frame with positions and the frame's plan; works on GPU state and the reference alike.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "tressvk/model/model.hpp"
#include "tressvk/model/planner.hpp"
#include "tressvk/reference/metrics.hpp"

namespace tressvk::reference {

struct PenetrationStats {
  double depth_rel = 0;           // deepest free vertex inside a capsule / the capsule's radius there (0: none)
  double post_contact_speed = 0;  // m/s, fastest vertex relative to the surface in the frame after a contact
  uint64_t contacts = 0;          // vertex-frames in contact (inside, or within kContactBand of the radius)
};

// How deep x is inside the tapered capsule, relative to its radius at the closest axis point (negative outside), and
// that point's axis parameter in t.
inline double capsule_depth_rel(Vec3 x, const CapsuleSim& c, double& t) {
  const Vec3 axis = c.p1 - c.p0;
  const double len2 = dot(axis, axis);
  t = len2 > 0 ? std::clamp(dot(x - c.p0, axis) / len2, 0.0, 1.0) : 0.0;
  const double r = c.r0 + (c.r1 - c.r0) * t;
  if (!(r > 0)) return -INFINITY;
  return (r - length(x - (c.p0 + t * axis))) / r;
}

class PenetrationTracker {
 public:
  // After each frame: the guides' positions (simulation space, the first G*N entries are read), the frame's plan
  // (its last step holds the frame's capsules) and the frame's dt. Pinned vertices are not counted (capsules never
  // move them). A frame that resets, teleports or drops steps starts the speed measurement over, and so does one that
  // does not directly follow the previous call's frame (`follows_previous` false).
  template <class A>
  void add(std::span<const A> pos, const FramePlan& plan, double dt, const ModelRest& rest,
           bool follows_previous = true) {
    const size_t count = std::min(pos.size(), rest.rest_pos.size());
    if (plan.steps.empty()) return;  // no step, nothing moved: keep the previous frame's state
    const Substep& last = plan.steps.back();
    bool jump = plan.dropped_steps > 0 || !follows_previous;
    for (const Substep& s : plan.steps) jump |= s.reset || std::abs(s.teleport.w) < 1.0 - 1e-12;
    std::vector<uint8_t> contact(count, 0);
    std::vector<Vec3> now(count);
    for (size_t i = 0; i < count; ++i) {
      now[i] = as_vec3(pos[i]);
      if (rest.inv_mass[i] == 0) continue;
      for (uint32_t c = 0; c < last.capsule_count; ++c) {
        double t = 0;
        const double d = capsule_depth_rel(now[i], last.capsules[c], t);
        if (d > -kContactBand) contact[i] = 1;
        if (d > stats_.depth_rel) stats_.depth_rel = d;
        // The speed after a contact in the previous frame, relative to the same capsule's surface point.
        if (!jump && have_previous_ && dt > 0 && c < prev_caps_.size() && prev_contact_[i]) {
          const CapsuleSim& pc = prev_caps_[c];
          const Vec3 surface_move = (last.capsules[c].p0 - pc.p0) * (1 - t) + (last.capsules[c].p1 - pc.p1) * t;
          const double v = length((now[i] - prev_[i]) - surface_move) / dt;
          if (std::isfinite(v)) stats_.post_contact_speed = std::max(stats_.post_contact_speed, v);
        }
      }
      stats_.contacts += contact[i];
    }
    prev_ = std::move(now);
    prev_contact_ = std::move(contact);
    prev_caps_.assign(last.capsules.begin(), last.capsules.begin() + last.capsule_count);
    have_previous_ = true;
  }
  const PenetrationStats& stats() const { return stats_; }

 private:
  PenetrationStats stats_;
  std::vector<Vec3> prev_;
  std::vector<uint8_t> prev_contact_;
  std::vector<CapsuleSim> prev_caps_;
  bool have_previous_ = false;
};

}  // namespace tressvk::reference
