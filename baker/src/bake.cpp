// The bake pipeline (see bake.hpp for the steps and asset.hpp for the conventions it produces).
#include "vec_math.hpp"

#include <tressvk/baker/bake.hpp>
#include <tressvk/baker/errors.hpp>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <numeric>
#include <span>

namespace tressvk::baker {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

Vec3 convert(const Vec3& p, const BakeOptions& o) {
  const double s = o.units_to_metres * o.scale;
  // Z-up to Y-up is a rotation of -90 degrees about X (right-handed stays right-handed): (x, y, z) -> (x, z, -y).
  if (o.up == UpAxis::kZ) return {p[0] * s, p[2] * s, -p[1] * s};
  return p * s;
}

struct ResampleError {
  double max = 0.0;
  double sum_sq = 0.0;
};

// Resamples a polyline to n vertices evenly spaced in arc length. `cum` holds the cumulative arc length.
void resample(std::span<const Vec3> pts, const std::vector<double>& cum, uint32_t n, std::vector<Vec3>& out,
              ResampleError& err) {
  out.resize(n);
  const double total = cum.back();
  size_t seg = 0;
  for (uint32_t i = 0; i < n; ++i) {
    const double s = total * i / (n - 1);
    while (seg + 2 < pts.size() && cum[seg + 1] < s) ++seg;
    const double span = cum[seg + 1] - cum[seg];
    const double t = span > 0 ? std::clamp((s - cum[seg]) / span, 0.0, 1.0) : 0.0;
    out[i] = pts[seg] + (pts[seg + 1] - pts[seg]) * t;
  }
  out.front() = pts.front();  // exact root and tip, whatever the rounding of s
  out.back() = pts.back();
  // Error: each input vertex against the resampled polyline at the same arc length.
  const double step = total / (n - 1);
  for (size_t k = 0; k < pts.size(); ++k) {
    const double u = cum[k] / step;
    const auto j = std::min<size_t>(static_cast<size_t>(u), n - 2);
    const double t = std::clamp(u - static_cast<double>(j), 0.0, 1.0);
    const Vec3 q = out[j] + (out[j + 1] - out[j]) * t;
    const double d = length(q - pts[k]);
    err.max = std::max(err.max, d);
    err.sum_sq += d * d;
  }
}

// Rest frames and rest edges exactly as documented in asset.hpp, from the positions the runtime will see.
void rest_frames(const std::vector<Vec3>& p, std::vector<Quat>& frames, std::vector<Vec3>& edges) {
  const size_t n = p.size();
  frames.resize(n);
  edges.assign(n, Vec3{0, 0, 0});
  const Vec3 x = normalized(p[1] - p[0]);
  // The asset axis least aligned with x (ties: X, then Y, then Z).
  size_t axis = 0;
  for (size_t k = 1; k < 3; ++k)
    if (std::abs(x[k]) < std::abs(x[axis])) axis = k;
  Vec3 a{0, 0, 0};
  a[axis] = 1.0;
  const Vec3 y = normalized(a - x * dot(a, x));
  const Vec3 z = cross(x, y);
  frames[0] = quat_from_axes(x, y, z);
  Vec3 prev_dir = x;
  for (size_t v = 1; v < n; ++v) {
    const Vec3 e = p[v] - p[v - 1];
    const double len = length(e);
    // A zero-length edge (possible only after float rounding of a hairpin) keeps the previous frame.
    if (len > 0) {
      const Vec3 dir = e * (1.0 / len);
      frames[v] = normalized(rotation_between(prev_dir, dir) * frames[v - 1]);
      prev_dir = dir;
    } else {
      frames[v] = frames[v - 1];
    }
  }
  for (size_t v = 0; v + 1 < n; ++v) edges[v] = rotate(conjugate(frames[v]), p[v + 1] - p[v]);
}

// Spreads n bits of v so that two zero bits separate each (for 3-D Morton codes).
uint64_t spread_bits(uint64_t v) {
  v &= 0x1FFFFF;
  v = (v | v << 32) & 0x1F00000000FFFFull;
  v = (v | v << 16) & 0x1F0000FF0000FFull;
  v = (v | v << 8) & 0x100F00F00F00F00Full;
  v = (v | v << 4) & 0x10C30C30C30C30C3ull;
  v = (v | v << 2) & 0x1249249249249249ull;
  return v;
}

uint64_t reverse_bits(uint64_t v, int bits) {
  uint64_t r = 0;
  for (int i = 0; i < bits; ++i, v >>= 1) r = (r << 1) | (v & 1u);
  return r;
}

// Level-of-detail order: any prefix of the result must be an even thinning of the groom. A random shuffle is
// even only on average (clumps and holes at small prefixes), so the guides are first sorted along a Z-order
// curve through their root positions (neighbours on the curve are neighbours on the scalp), then taken in
// bit-reversed curve order: a prefix of m guides takes about every (G/m)-th guide along the curve, which spreads
// it over the whole scalp at every m. The seed picks a random starting point on the curve and a random
// tie-break, so different seeds give different (equally even) orders.
std::vector<uint32_t> lod_order(const std::vector<uint32_t>& kept, const std::vector<Vec3>& pts,
                                const std::vector<uint32_t>& begin, uint64_t seed) {
  const size_t g = kept.size();
  if (g < 2) return kept;
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (uint32_t s : kept)
    for (size_t a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], pts[begin[s]][a]);
      hi[a] = std::max(hi[a], pts[begin[s]][a]);
    }
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  const double q = extent > 0 ? static_cast<double>(0x1FFFFF) / extent : 0.0;
  Random rng(seed ^ 0x5F3759DFull);
  struct Key {
    uint64_t morton, tie;
    uint32_t strand;
  };
  std::vector<Key> keys(g);
  for (size_t i = 0; i < g; ++i) {
    const Vec3& r = pts[begin[kept[i]]];
    uint64_t m = 0;
    for (size_t a = 0; a < 3; ++a) {
      // A subnormal extent makes q infinite and 0 * q NaN: clamp before the cast (same keys otherwise).
      double c = (r[a] - lo[a]) * q;
      if (!(c >= 0.0)) c = 0.0;
      if (c > static_cast<double>(0x1FFFFF)) c = static_cast<double>(0x1FFFFF);
      m |= spread_bits(static_cast<uint64_t>(c)) << a;
    }
    keys[i] = {m, rng.next(), kept[i]};
  }
  std::sort(keys.begin(), keys.end(), [](const Key& x, const Key& y) {
    return x.morton != y.morton ? x.morton < y.morton : x.tie != y.tie ? x.tie < y.tie : x.strand < y.strand;
  });
  int bits = 0;
  while ((uint64_t{1} << bits) < g) ++bits;
  const uint64_t offset = rng.below(g);
  std::vector<uint32_t> order;
  order.reserve(g);
  for (uint64_t j = 0; j < (uint64_t{1} << bits); ++j) {
    const uint64_t k = reverse_bits(j, bits);
    if (k < g) order.push_back(keys[(k + offset) % g].strand);
  }
  return order;
}

std::array<float, 4> to_float4(const Quat& q) {
  return {static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z), static_cast<float>(q.w)};
}

}  // namespace

std::string bake_settings_json(const BakeOptions& o) {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "{\"vertices\":%u,\"pin\":%u,\"follow\":%u,\"follow_radius_m\":%.9g,\"tip_separation\":%.9g,"
                "\"seed\":%llu,\"units_to_metres\":%.9g,\"scale\":%.9g,\"up\":\"%s\",\"shuffle\":%s}",
                o.vertices_per_strand, o.pin, o.follow_per_guide, o.follow_radius, double{o.tip_separation},
                static_cast<unsigned long long>(o.seed), o.units_to_metres, o.scale, o.up == UpAxis::kZ ? "z" : "y",
                o.shuffle ? "true" : "false");
  return buf;
}

asset::HairAsset bake(const RawGroom& groom, const BakeOptions& o, BakeReport* report_out) {
  const uint32_t n = o.vertices_per_strand;
  if (n < asset::kMinVerticesPerStrand || n > asset::kMaxVerticesPerStrand)
    throw InputError("--vertices " + std::to_string(n) + " is outside 4..128");
  if (!(o.units_to_metres > 0) || !(o.scale > 0) || !std::isfinite(o.scale))
    throw InputError("--scale must be a positive finite number");
  if (!std::isfinite(o.tip_separation) || o.tip_separation < 0)
    throw InputError("--tip-separation must be a finite number >= 0");
  if (o.follow_per_guide > asset::kMaxFollowPerGuide)
    throw InputError("--follow " + std::to_string(o.follow_per_guide) + " exceeds " +
                     std::to_string(asset::kMaxFollowPerGuide));
  BakeReport rep;
  rep.input_strands = groom.strand_count() + groom.skipped_invalid;
  rep.input_vertices = groom.input_vertices ? groom.input_vertices : groom.points.size();
  rep.skipped_invalid = groom.skipped_invalid;
  rep.bone_influences_dropped = groom.bone_influences_dropped;

  // 1. Scale-aware tolerances from the groom itself, in metres of the final asset: the unit conversion is a
  // rotation and a uniform scale, so converted lengths are the input lengths times that scale.
  const double to_metres = o.units_to_metres * o.scale;
  const size_t strands = groom.strand_count();
  {
    std::vector<double> seg;
    seg.reserve(groom.points.size());
    for (size_t s = 0; s < strands; ++s)
      for (uint32_t i = groom.strand_begin[s] + 1; i < groom.strand_begin[s + 1]; ++i) {
        const double l = length(groom.points[i] - groom.points[i - 1]) * to_metres;
        if (l > 0) seg.push_back(l);
      }
    rep.median_segment_length = median(std::move(seg));
  }
  rep.merge_tolerance = o.merge_fraction * rep.median_segment_length;

  // 2. Convert units and axes, and merge repeated vertices and sub-tolerance segments, strand by strand (roots
  // and tips are kept). The result is flat: strand s is clean[begin[s] .. begin[s+1]).
  std::vector<Vec3> clean;
  clean.reserve(groom.points.size());
  std::vector<uint32_t> begin(strands + 1, 0);
  std::vector<double> strand_length(strands, 0.0);
  for (size_t s = 0; s < strands; ++s) {
    const uint32_t b = groom.strand_begin[s], e = groom.strand_begin[s + 1];
    const size_t first = clean.size();
    for (uint32_t i = b; i < e; ++i) {
      const Vec3 q = convert(groom.points[i], o);
      if (!std::isfinite(q[0]) || !std::isfinite(q[1]) || !std::isfinite(q[2]))
        throw InputError("strand " + std::to_string(s) + ": a coordinate overflows after unit conversion and scaling");
      if (clean.size() > first && length(q - clean.back()) <= rep.merge_tolerance) {
        ++rep.merged_vertices;
        if (i + 1 == e && clean.size() - first > 1) clean.back() = q;  // keep the real tip, not the merged vertex
        continue;
      }
      clean.push_back(q);
    }
    begin[s + 1] = static_cast<uint32_t>(clean.size());
    for (size_t i = first + 1; i < clean.size(); ++i) strand_length[s] += length(clean[i] - clean[i - 1]);
    if (!std::isfinite(strand_length[s]))
      throw InputError("strand " + std::to_string(s) + ": its length overflows (coordinates far out of range)");
  }
  auto count = [&](size_t s) { return begin[s + 1] - begin[s]; };
  {
    std::vector<double> lengths;
    for (size_t s = 0; s < strands; ++s)
      if (count(s) >= 2) lengths.push_back(strand_length[s]);
    rep.median_strand_length = median(std::move(lengths));
  }
  rep.min_strand_length = o.min_length_fraction * rep.median_strand_length;

  // 3. Keep strands that are long enough.
  std::vector<uint32_t> kept;
  for (size_t s = 0; s < strands; ++s) {
    if (count(s) < 2 || strand_length[s] < rep.min_strand_length || !(strand_length[s] > 0)) {
      ++rep.dropped_short;
      continue;
    }
    kept.push_back(static_cast<uint32_t>(s));
  }
  if (kept.empty()) throw InputError("no strand is left to bake (all " + std::to_string(strands) +
                                     " strands are degenerate or shorter than the length threshold)");
  if (kept.size() > asset::kMaxRenderedVertices / (uint64_t{n} * (1 + o.follow_per_guide)))
    throw InputError("too many strands for one asset: " + std::to_string(kept.size()) + " guides x (1 + " +
                     std::to_string(o.follow_per_guide) + " follows) x " + std::to_string(n) +
                     " vertices exceeds the limit of " + std::to_string(asset::kMaxRenderedVertices) +
                     " rendered vertices");

  // 4. Level-of-detail order (see lod_order).
  if (o.shuffle) kept = lod_order(kept, clean, begin, o.seed);
  const size_t g = kept.size();

  // 5. Origin: the centre of the kept strands' bounds, rounded to a whole millimetre (resampled vertices lie on
  // the strands, so inside these bounds).
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (uint32_t s : kept)
    for (uint32_t i = begin[s]; i < begin[s + 1]; ++i)
      for (size_t k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], clean[i][k]);
        hi[k] = std::max(hi[k], clean[i][k]);
      }

  asset::HairAsset a;
  a.vertices_per_strand = n;
  a.follow_per_guide = o.follow_per_guide;
  a.tip_separation = o.tip_separation;
  for (size_t k = 0; k < 3; ++k) a.origin[k] = std::round((lo[k] + hi[k]) * 0.5 * 1000.0) / 1000.0 + 0.0;  // + 0.0: no negative zero
  const Vec3 origin{a.origin[0], a.origin[1], a.origin[2]};

  // 7. Per-vertex data, computed from the float32 positions the runtime will actually see.
  a.rest_positions.resize(g * n);
  a.rest_lengths.resize(g * n);
  a.rest_frames.resize(g * n);
  a.rest_edge_local.resize(g * n);
  std::vector<Vec3> p(n);
  std::vector<Quat> frames;
  std::vector<Vec3> edges;
  std::vector<double> cum;
  std::vector<Vec3> resampled;
  ResampleError err;
  uint64_t error_samples = 0;
  const uint32_t pin = std::min(o.pin, n);
  for (size_t k = 0; k < g; ++k) {
    // Resample (double), with the error against the input vertices.
    const std::span<const Vec3> c(clean.data() + begin[kept[k]], count(kept[k]));
    cum.assign(c.size(), 0.0);
    for (size_t i = 1; i < c.size(); ++i) cum[i] = cum[i - 1] + length(c[i] - c[i - 1]);
    ResampleError e;
    resample(c, cum, n, resampled, e);
    err.max = std::max(err.max, e.max);
    err.sum_sq += e.sum_sq;
    error_samples += c.size();
    rep.max_relative_resample_error = std::max(rep.max_relative_resample_error, e.max / cum.back());

    const bool pin_tip = groom.strand_pin_tip[kept[k]] != 0;
    for (uint32_t v = 0; v < n; ++v) {
      const Vec3 rel = resampled[v] - origin;
      // float32 must hold the position and every length and edge made from two of them (|a - b| <= 2 sqrt(3) max).
      constexpr double kMaxCoordinate = std::numeric_limits<float>::max() / 8.0;
      if (!(std::abs(rel[0]) < kMaxCoordinate && std::abs(rel[1]) < kMaxCoordinate && std::abs(rel[2]) < kMaxCoordinate))
        throw InputError("strand " + std::to_string(kept[k]) + ": a vertex lies " + std::to_string(length(rel)) +
                         " m from the asset origin, beyond what float32 holds (check --units/--scale and for "
                         "stray far-away vertices)");
      const std::array<float, 3> f{static_cast<float>(rel[0]), static_cast<float>(rel[1]), static_cast<float>(rel[2])};
      p[v] = {f[0], f[1], f[2]};
      const bool pinned = v < pin || (pin_tip && v + pin >= n);
      a.rest_positions[k * n + v] = {f[0], f[1], f[2], pinned ? 0.0f : 1.0f};
    }
    // Every segment must survive as a normal float32 length (subnormals lose their relative precision).
    for (uint32_t v = 0; v + 1 < n; ++v)
      if (!(length(p[v + 1] - p[v]) >= std::numeric_limits<float>::min()))
        throw InputError("strand " + std::to_string(kept[k]) + ": its segments vanish in float32 at a distance of " +
                         std::to_string(length(p[v])) + " m from the asset origin (the groom spans too wide a range " +
                         "for its strand sizes; check for stray far-away vertices)");
    rest_frames(p, frames, edges);
    for (uint32_t v = 0; v < n; ++v) {
      a.rest_lengths[k * n + v] = v + 1 < n ? static_cast<float>(length(p[v + 1] - p[v])) : 0.0f;
      a.rest_frames[k * n + v] = to_float4(frames[v]);
      a.rest_edge_local[k * n + v] = {static_cast<float>(edges[v][0]), static_cast<float>(edges[v][1]),
                                       static_cast<float>(edges[v][2]), 0.0f};
    }
  }

  rep.max_resample_error = err.max;
  rep.rms_resample_error = error_samples ? std::sqrt(err.sum_sq / static_cast<double>(error_samples)) : 0.0;

  // 8. Groups: only those still used, in first-use order of the original group list.
  std::vector<int> group_map(groom.group_names.size(), -1);
  std::vector<bool> used(groom.group_names.size(), false);
  for (uint32_t s : kept) used[groom.strand_group[s]] = true;
  for (size_t i = 0; i < used.size(); ++i) {
    if (!used[i]) continue;
    group_map[i] = static_cast<int>(a.groups.size());
    std::string name = groom.group_names[i].empty() ? "hair" : groom.group_names[i];
    // Names must be unique in an asset; OBJ files can repeat a `g` name for unrelated objects.
    std::string unique = name;
    for (int suffix = 2; std::any_of(a.groups.begin(), a.groups.end(), [&](const auto& x) { return x.name == unique; });
         ++suffix)
      unique = name + "#" + std::to_string(suffix);
    a.groups.push_back({unique});
  }
  if (a.groups.size() > 65535) throw InputError("more than 65535 strand groups");
  a.guide_group.resize(g);
  for (size_t k = 0; k < g; ++k) a.guide_group[k] = static_cast<uint16_t>(group_map[groom.strand_group[kept[k]]]);

  if (!groom.strand_uv.empty()) {
    a.root_uv.resize(g);
    for (size_t k = 0; k < g; ++k) a.root_uv[k] = groom.strand_uv[kept[k]];
  }
  if (!groom.strand_bones.empty()) {
    a.bone_names = groom.bone_names;
    a.bone_weights.resize(g);
    for (size_t k = 0; k < g; ++k) a.bone_weights[k] = groom.strand_bones[kept[k]];
  }

  // 9. Follow hairs: uniform in a disc of radius R around the guide root, perpendicular to the root edge, stored
  // in the root frame (local +X is the root edge, so the offset has x = 0).
  rep.follow_radius = o.follow_radius >= 0 ? o.follow_radius * o.units_to_metres * o.scale : 0.05 * rep.median_strand_length;
  a.follow_offsets.resize(g * o.follow_per_guide);
  Random follow_rng(o.seed * 0x9E3779B97F4A7C15ull + 17);
  for (size_t k = 0; k < g; ++k)
    for (uint32_t f = 0; f < o.follow_per_guide; ++f) {
      const double r = rep.follow_radius * std::sqrt(follow_rng.uniform());
      const double t = 2.0 * 3.14159265358979323846 * follow_rng.uniform();
      a.follow_offsets[k * o.follow_per_guide + f] = {0.0f, static_cast<float>(r * std::cos(t)),
                                                      static_cast<float>(r * std::sin(t)), 0.0f};
    }

  // Stored with the radius actually used (metres), not the "automatic" marker.
  BakeOptions settings = o;
  settings.follow_radius = rep.follow_radius;
  a.bake_settings = bake_settings_json(settings);

  rep.guides = g;
  rep.output_vertices = g * n;
  if (report_out) *report_out = rep;
  return a;
}

}  // namespace tressvk::baker
