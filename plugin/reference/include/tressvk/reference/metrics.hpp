// Metrics shared by the tests and the bench. Every length is divided by the groom's median strand rest length, so
// the numbers mean the same for any scale or unit.
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "tressvk/model/gpu_layout.hpp"
#include "tressvk/model/math.hpp"
#include "tressvk/model/model.hpp"

namespace tressvk::reference {

// The reference is written in the runtime model's terms (planner, rest data, math: tressvk::model).
using namespace tressvk::model;

inline Vec3 as_vec3(const Vec3& v) { return v; }
inline Vec3 as_vec3(const sim::Vec4& v) { return {v[0], v[1], v[2]}; }
inline Vec3 as_vec3(const std::array<double, 3>& v) { return {v[0], v[1], v[2]}; }

struct ErrorStats {
  double max_rel = 0;  // largest vertex distance / median strand length
  double rms_rel = 0;  // RMS of the distances / median strand length
  uint64_t count = 0;
};

// Distance between two states, vertex by vertex over the shorter of the two. Non-finite distances count as +inf.
template <class A, class B>
ErrorStats position_error(std::span<const A> a, std::span<const B> b, double median_length) {
  ErrorStats e;
  const size_t n = a.size() < b.size() ? a.size() : b.size();
  double sum = 0;
  for (size_t i = 0; i < n; ++i) {
    double d = length(as_vec3(a[i]) - as_vec3(b[i]));
    if (!std::isfinite(d)) d = INFINITY;
    e.max_rel = d > e.max_rel ? d : e.max_rel;
    sum += d * d;
  }
  e.count = n;
  if (n > 0 && median_length > 0) {
    e.max_rel /= median_length;
    e.rms_rel = std::sqrt(sum / static_cast<double>(n)) / median_length;
  }
  return e;
}

// The model error of a trajectory (docs/accuracy.md): the distance of every vertex at every sampled frame from the
// same vertex in a reference trajectory (normally the converged one: the same model stepped far finer), relative to
// the median strand length; rms over all samples, and the max. Frames are compared index by index.
inline ErrorStats trajectory_error(const std::vector<std::vector<Vec3>>& a, const std::vector<std::vector<Vec3>>& b,
                                   double median_length) {
  ErrorStats e;
  double sum = 0;
  const size_t frames = a.size() < b.size() ? a.size() : b.size();
  for (size_t f = 0; f < frames; ++f) {
    const ErrorStats one = position_error(std::span<const Vec3>(a[f]), std::span<const Vec3>(b[f]), 1.0);
    e.max_rel = one.max_rel > e.max_rel ? one.max_rel : e.max_rel;
    sum += one.rms_rel * one.rms_rel * static_cast<double>(one.count);
    e.count += one.count;
  }
  if (e.count > 0 && median_length > 0) {
    e.max_rel /= median_length;
    e.rms_rel = std::sqrt(sum / static_cast<double>(e.count)) / median_length;
  }
  return e;
}

// Segments whose rest length is below this fraction of their strand's mean segment are left out of the stretch
// statistic (a sub-micrometre segment's relative stretch measures rounding, not the solver).
inline constexpr double kStretchMinRestRel = 1e-2;

struct StretchStats {
  double mean = 0;     // mean of |l - l0| / l0
  double max = 0;
  uint64_t segments = 0;
};

// Over the guide segments (the first G*N positions).
template <class A>
StretchStats stretch(std::span<const A> pos, const ModelRest& rest) {
  StretchStats s;
  const uint32_t n = rest.vertices_per_strand;
  double sum = 0;
  for (uint32_t g = 0; g < rest.guide_count; ++g) {
    const double min_rest = kStretchMinRestRel * rest.strand_length[g] / static_cast<double>(n - 1);
    for (uint32_t v = 0; v + 1 < n; ++v) {
      const size_t i = size_t{g} * n + v;
      const double l0 = rest.rest_length[i];
      if (!(l0 > min_rest) || i + 1 >= pos.size()) continue;
      const double r = std::abs(length(as_vec3(pos[i + 1]) - as_vec3(pos[i])) - l0) / l0;
      const double rr = std::isfinite(r) ? r : INFINITY;
      sum += rr;
      s.max = rr > s.max ? rr : s.max;
      ++s.segments;
    }
  }
  if (s.segments) s.mean = sum / static_cast<double>(s.segments);
  return s;
}

struct HealthStats {
  uint32_t nan_strands = 0;       // strands with a non-finite position
  uint32_t exploded_strands = 0;  // strands with a vertex farther than 1.5 strand lengths from their root
};

// Over every strand present in pos (guides, then follow layers; a follow is measured against its own rest
// length, which tip separation makes longer than its guide's).
template <class A>
HealthStats health(std::span<const A> pos, const ModelRest& rest) {
  HealthStats h;
  const uint32_t n = rest.vertices_per_strand;
  const size_t strands = pos.size() / n;
  for (size_t s = 0; s < strands; ++s) {
    const uint32_t g = static_cast<uint32_t>(s % rest.guide_count);
    const size_t layer = s / rest.guide_count;
    const double len = layer == 0 || rest.follow_length.empty()
                           ? rest.strand_length[g]
                           : rest.follow_length[size_t{g} * rest.follow_per_guide + (layer - 1)];
    const Vec3 root = as_vec3(pos[s * n]);
    bool bad = false, far = false;
    for (uint32_t v = 0; v < n; ++v) {
      const Vec3 p = as_vec3(pos[s * n + v]);
      if (!is_finite(p)) bad = true;
      else if (length(p - root) > 1.5 * len) far = true;
    }
    if (bad) ++h.nan_strands;
    else if (far) ++h.exploded_strands;
  }
  return h;
}

}  // namespace tressvk::reference
