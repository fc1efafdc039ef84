// The groom generator (see groom.hpp for the model): roots on the scalp, combed and gravity-aware growth over a
// fitted head shape, clumps, curls and frizz, then the ordinary bake.
#include "vec_math.hpp"

#include <tressvk/baker/bake.hpp>
#include <tressvk/baker/errors.hpp>
#include <tressvk/baker/groom.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>

namespace tressvk::baker {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kSteps = 96;            // polyline segments per grown strand (the bake resamples)
constexpr double kFallLength = 0.06;  // m of strand over which gravity 1 turns a horizontal strand down

// An axis-aligned ellipsoid the strands slide over: the head's shape as the scalp shows it.
struct HeadShape {
  bool valid = false;
  Vec3 center{};
  Vec3 radii{1, 1, 1};
  // Radial "size" of p: 1 on the surface, < 1 inside.
  double size(const Vec3& p) const {
    const Vec3 d = p - center;
    return std::sqrt(d[0] * d[0] / (radii[0] * radii[0]) + d[1] * d[1] / (radii[1] * radii[1]) +
                     d[2] * d[2] / (radii[2] * radii[2]));
  }
  // Hair does not hang in front of the face: a point in front of the face (towards +Z, from the eyebrows down to
  // the chin, within the head's width) moves sideways to the face's edge, so strands frame the face.
  Vec3 off_face(const Vec3& p, double side) const {
    const Vec3 d = p - center;
    // Heights in the mean radius: a scalp that is only a cap leaves the fitted height (y radius) uncertain.
    const double fx = 0.85 * radii[0], rm = (radii[0] + radii[1] + radii[2]) / 3.0;
    if (d[2] > 0.1 * radii[2] && d[1] < 0.3 * rm && d[1] > -1.6 * rm && std::abs(d[0]) < fx)
      return {center[0] + (side >= 0 ? fx : -fx), p[1], p[2]};
    return p;
  }
  // p pushed out radially to size `shell` when it is inside it.
  Vec3 push_out(const Vec3& p, double shell) const {
    const double q = size(p);
    if (q >= shell || q <= 1e-12) return p;
    return center + (p - center) * (shell / q);
  }
};

// Solves the n x n system a x = b (row-major a) by Gaussian elimination with partial pivoting. False if singular.
bool solve(int n, std::vector<double> a, std::vector<double> b, std::vector<double>& x) {
  for (int c = 0; c < n; ++c) {
    int piv = c;
    for (int r = c + 1; r < n; ++r)
      if (std::abs(a[r * n + c]) > std::abs(a[piv * n + c])) piv = r;
    if (std::abs(a[piv * n + c]) < 1e-300) return false;
    if (piv != c) {
      for (int k = 0; k < n; ++k) std::swap(a[c * n + k], a[piv * n + k]);
      std::swap(b[c], b[piv]);
    }
    for (int r = c + 1; r < n; ++r) {
      const double f = a[r * n + c] / a[c * n + c];
      for (int k = c; k < n; ++k) a[r * n + k] -= f * a[c * n + k];
      b[r] -= f * b[c];
    }
  }
  x.assign(n, 0.0);
  for (int r = n - 1; r >= 0; --r) {
    double s = b[r];
    for (int k = r + 1; k < n; ++k) s -= a[r * n + k] * x[k];
    x[r] = s / a[r * n + r];
  }
  return std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); });
}

// Least-squares fit of an axis-aligned ellipsoid A x^2 + B y^2 + C z^2 + D x + E y + F z = 1 (points relative
// to their centroid, in units of their extent for conditioning); a sphere when that is not an ellipsoid.
HeadShape fit_head(const std::vector<Vec3>& pts) {
  HeadShape h;
  if (pts.size() < 6) return h;
  Vec3 mean{};
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const Vec3& p : pts) {
    mean = mean + p;
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  }
  mean = mean * (1.0 / static_cast<double>(pts.size()));
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  if (!(extent > 0)) return h;
  const double inv = 1.0 / extent;
  auto accumulate = [&](int n, auto&& row, auto&& rhs) {
    std::vector<double> m(static_cast<size_t>(n * n), 0.0), b(static_cast<size_t>(n), 0.0), x;
    std::vector<double> r(static_cast<size_t>(n));
    for (const Vec3& p0 : pts) {
      const Vec3 p = (p0 - mean) * inv;
      row(p, r.data());
      const double y = rhs(p);
      for (int i = 0; i < n; ++i) {
        b[i] += r[i] * y;
        for (int k = 0; k < n; ++k) m[i * n + k] += r[i] * r[k];
      }
    }
    if (!solve(n, m, b, x)) x.clear();
    return x;
  };
  const auto e = accumulate(
      6,
      [](const Vec3& p, double* r) {
        r[0] = p[0] * p[0]; r[1] = p[1] * p[1]; r[2] = p[2] * p[2];
        r[3] = p[0]; r[4] = p[1]; r[5] = p[2];
      },
      [](const Vec3&) { return 1.0; });
  if (e.size() == 6 && e[0] > 0 && e[1] > 0 && e[2] > 0) {
    const Vec3 c{-e[3] / (2 * e[0]), -e[4] / (2 * e[1]), -e[5] / (2 * e[2])};
    const double k = 1.0 + e[0] * c[0] * c[0] + e[1] * c[1] * c[1] + e[2] * c[2] * c[2];
    const Vec3 r{std::sqrt(k / e[0]), std::sqrt(k / e[1]), std::sqrt(k / e[2])};
    const double rmax = std::max({r[0], r[1], r[2]}), rmin = std::min({r[0], r[1], r[2]});
    if (k > 0 && std::isfinite(rmax) && rmax < 4.0 && rmin > 0.05) {
      h.valid = true;
      h.center = mean + c * extent;
      h.radii = r * extent;
      return h;
    }
  }
  // x^2 + y^2 + z^2 = D x + E y + F z + G.
  const auto s = accumulate(
      4, [](const Vec3& p, double* r) { r[0] = p[0]; r[1] = p[1]; r[2] = p[2]; r[3] = 1.0; },
      [](const Vec3& p) { return dot(p, p); });
  if (s.size() == 4) {
    const Vec3 c{s[0] / 2, s[1] / 2, s[2] / 2};
    const double r2 = s[3] + dot(c, c);
    if (r2 > 0 && std::sqrt(r2) < 4.0) {
      h.valid = true;
      h.center = mean + c * extent;
      const double r = std::sqrt(r2) * extent;
      h.radii = {r, r, r};
    }
  }
  return h;
}

void check_params(const GroomParams& p) {
  auto bad = [](const std::string& what) { throw InputError("groom: " + what); };
  auto in = [](double v, double lo, double hi) { return std::isfinite(v) && v >= lo && v <= hi; };
  if (p.guides < 1 || p.guides > 200000) bad("--guides must be 1..200000");
  if (p.follow > 64) bad("--follow must be 0..64");
  if (p.vertices < asset::kMinVerticesPerStrand || p.vertices > asset::kMaxVerticesPerStrand)
    bad("--vertices must be 4..128");
  if (!in(p.length, 1e-4, 10.0)) bad("--length must be 0.0001..10 m");
  if (!in(p.length_variation, 0, 1)) bad("--length-variation must be 0..1");
  if (!in(p.parting, -1, 1)) bad("--parting must be -1..1 (or 'none')");
  if (!in(p.gravity, 0, 10)) bad("--gravity must be 0..10");
  if (!in(p.lift, 0, 1)) bad("--lift must be 0..1");
  if (!in(p.clump, 0, 1)) bad("--clump must be 0..1");
  if (!in(p.clump_size, 1, 1e6)) bad("--clump-size must be >= 1 guide");
  if (!in(p.curl_radius, 0, 1)) bad("--curl-radius must be 0..1 m");
  if (!in(p.curl_frequency, 0, 1000)) bad("--curl-frequency must be 0..1000 turns per metre");
  if (!in(p.frizz, 0, 1)) bad("--frizz must be 0..1 m");
  if (!in(p.taper, 0, 1)) bad("--taper must be 0..1");
}

Vec3 any_perpendicular(const Vec3& t) {
  const Vec3 a = std::abs(t[1]) < 0.9 ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
  return normalized(cross(t, a));
}

// Parallel-transported frames (u, w) along a polyline; u starts perpendicular to the first segment and to +Y.
void transport_frames(const std::vector<Vec3>& pts, std::vector<Vec3>& us, std::vector<Vec3>& ws) {
  const size_t n = pts.size();
  us.assign(n, Vec3{1, 0, 0});
  ws.assign(n, Vec3{0, 0, 1});
  Vec3 t_prev = normalized(pts[1] - pts[0]);
  Vec3 u = any_perpendicular(t_prev);
  for (size_t k = 0; k < n; ++k) {
    const Vec3 t = normalized(pts[std::min(k + 1, n - 1)] - pts[k == 0 ? 0 : k - 1]);
    if (length(t) > 0) {
      u = rotate(rotation_between(t_prev, t), u);
      u = normalized(u - t * dot(u, t));
      t_prev = t;
    }
    us[k] = u;
    ws[k] = cross(t_prev, u);
  }
}

}  // namespace

std::vector<std::string> groom_preset_names() { return {"straight", "curly"}; }

GroomParams groom_preset(std::string_view name) {
  GroomParams p;
  if (name == "straight") {
    // Shoulder-length straight hair parted on the head's left, lightly clumped, tapered tips.
    p.length = 0.30;
    p.length_variation = 0.08;
    p.parting_on = true;
    p.parting = 0.3;
    p.gravity = 1.0;
    p.lift = 0.25;
    p.clump = 0.3;
    p.clump_size = 8;
    p.frizz = 0.0015;
    p.taper = 0.2;
    p.vertices = 32;
    return p;
  }
  if (name == "curly") {
    // Shoulder-length ringlets: no parting, clumped curls with a little frizz (the curls give the volume; a higher
    // lift stood the hairline up, and the simulation then let those curls fall over the face).
    p.length = 0.24;
    p.length_variation = 0.15;
    p.parting_on = false;
    p.gravity = 0.7;
    p.lift = 0.25;
    p.clump = 0.6;
    p.clump_size = 6;
    p.curl_radius = 0.009;
    p.curl_frequency = 22;
    p.frizz = 0.003;
    p.taper = 0.3;
    p.vertices = 48;
    return p;
  }
  std::string names;
  for (const auto& n : groom_preset_names()) names += (names.empty() ? "" : ", ") + n;
  throw InputError("unknown groom preset '" + std::string(name) + "' (presets: " + names + ")");
}

RawGroom grow_groom(const GroomScalp& scalp, const GroomParams& P, GroomReport* report) {
  check_params(P);
  const size_t nv = scalp.vertices.size();
  if (!scalp.length_map.empty() && scalp.length_map.size() != nv)
    throw InputError("groom: the length map has " + std::to_string(scalp.length_map.size()) + " values for " +
                     std::to_string(nv) + " vertices");
  // Triangles with area, cumulative areas, vertex normals (area-weighted).
  std::vector<std::array<uint32_t, 3>> tris;
  std::vector<double> cum{0.0};
  std::vector<Vec3> vn(nv, Vec3{0, 0, 0});
  std::vector<uint8_t> used(nv, 0);
  for (size_t t = 0; t < scalp.triangles.size(); ++t) {
    const auto& tri = scalp.triangles[t];
    for (uint32_t i : tri)
      if (i >= nv) throw InputError("groom: scalp triangle " + std::to_string(t) + " uses vertex " +
                                    std::to_string(i) + " of " + std::to_string(nv));
    const Vec3 n = cross(scalp.vertices[tri[1]] - scalp.vertices[tri[0]], scalp.vertices[tri[2]] - scalp.vertices[tri[0]]);
    const double area = 0.5 * length(n);
    if (!(area > 0) || !std::isfinite(area)) continue;
    tris.push_back(tri);
    cum.push_back(cum.back() + area);
    for (uint32_t i : tri) {
      vn[i] = vn[i] + n;
      used[i] = 1;
    }
  }
  if (tris.empty()) throw InputError("groom: the scalp has no faces with area");
  std::vector<Vec3> used_pts;
  for (size_t i = 0; i < nv; ++i)
    if (used[i]) used_pts.push_back(scalp.vertices[i]);
  const HeadShape head = fit_head(used_pts);
  Vec3 centroid{};
  for (const Vec3& p : used_pts) centroid = centroid + p;
  centroid = centroid * (1.0 / static_cast<double>(used_pts.size()));
  const Vec3 center = head.valid ? head.center : centroid;
  const Vec3 radii = head.valid ? head.radii : Vec3{1, 1, 1};
  const double total_area = cum.back();

  Random rng(P.seed);
  const uint32_t G = P.guides;
  struct Root {
    Vec3 p, n;
    double length_scale;
  };
  std::vector<Root> roots(G);
  for (uint32_t i = 0; i < G; ++i) {
    // Stratified over the area: root i falls in the i-th G-quantile of the scalp's area.
    const double u = (i + rng.uniform()) / G * total_area;
    const size_t t = std::min<size_t>(
        static_cast<size_t>(std::upper_bound(cum.begin(), cum.end(), u) - cum.begin()) - 1, tris.size() - 1);
    const double a = std::clamp((u - cum[t]) / (cum[t + 1] - cum[t]), 0.0, 1.0);
    const double b = rng.uniform();
    const double sa = std::sqrt(a);
    const double w0 = 1.0 - sa, w1 = sa * (1.0 - b), w2 = sa * b;
    const auto& tri = tris[t];
    Root r;
    r.p = scalp.vertices[tri[0]] * w0 + scalp.vertices[tri[1]] * w1 + scalp.vertices[tri[2]] * w2;
    Vec3 n = normalized(vn[tri[0]] * w0 + vn[tri[1]] * w1 + vn[tri[2]] * w2);
    if (length(n) == 0) n = normalized(cross(scalp.vertices[tri[1]] - scalp.vertices[tri[0]],
                                             scalp.vertices[tri[2]] - scalp.vertices[tri[0]]));
    if (head.valid && dot(n, r.p - center) < 0) n = n * -1.0;  // faces wound inwards
    r.n = n;
    r.length_scale = scalp.length_map.empty()
                         ? 1.0
                         : std::max(0.0, scalp.length_map[tri[0]] * w0 + scalp.length_map[tri[1]] * w1 +
                                             scalp.length_map[tri[2]] * w2);
    roots[i] = r;
  }

  // 1-3: length, comb and gravity-aware growth of each strand's core path.
  const Vec3 down{0, -1, 0};
  const double part_x = center[0] + P.parting * radii[0];
  std::vector<std::vector<Vec3>> core(G);
  std::vector<double> lengths(G);
  std::vector<double> shells(G);
  std::vector<double> sides(G);  // which side of the face a strand passes on: its root's (its parting side)
  for (uint32_t i = 0; i < G; ++i) {
    const Root& r = roots[i];
    const double len = P.length * r.length_scale * (1.0 + P.length_variation * (2.0 * rng.uniform() - 1.0));
    lengths[i] = std::max(len, 1e-4 * P.length);
    const Vec3 rel = r.p - center;
    const double front = std::clamp(rel[2] / radii[2], -1.0, 1.0);  // +1 at the forehead, -1 at the back
    sides[i] = (P.parting_on ? r.p[0] - part_x : rel[0]) >= 0 ? 1.0 : -1.0;
    Vec3 away;
    if (P.parting_on) {
      away = Vec3{r.p[0] >= part_x ? 1.0 : -1.0, 0.0, 0.0};
    } else {
      away = normalized(Vec3{rel[0], 0.0, std::min(rel[2], 0.0)});  // out to the sides and back, never forwards
    }
    // Away from the parting, back from the face, a little down.
    const Vec3 want = away * (0.6 + 0.2 * std::max(0.0, front)) + Vec3{0, 0, -1} * (0.25 + 1.3 * std::max(0.0, front)) +
                      down * 0.3;
    Vec3 tangent = want - r.n * dot(want, r.n);
    tangent = length(tangent) > 1e-9 ? normalized(tangent) : any_perpendicular(r.n);
    Vec3 dir = normalized(r.n * P.lift + tangent * (1.0 - P.lift));
    // Each strand lies on its own layer over the head, 1 to 5 % (more with lift) of the head's size outside it.
    const double root_size = head.valid ? head.size(r.p) : 1.0;
    shells[i] = std::max(root_size, 1.0) * (1.0 + 0.01 + (0.04 + 0.25 * P.lift * P.lift) * rng.uniform());
    const double ds = lengths[i] / kSteps;
    std::vector<Vec3>& pts = core[i];
    pts.reserve(kSteps + 1);
    Vec3 p = r.p;
    pts.push_back(p);
    for (int k = 1; k <= kSteps; ++k) {
      dir = normalized(dir + down * (P.gravity * ds / kFallLength));
      Vec3 q = p + dir * ds;
      if (head.valid) {
        // Over the top of the head the strand lies on its layer (combed hair follows the skull); below the
        // widest part it is only kept out of the head and falls free.
        const Vec3 rq = q - center;
        if (rq[1] / radii[1] > -0.15 * P.gravity)
          q = head.center + rq * (shells[i] / std::max(head.size(q), 1e-12));
        else
          q = head.push_out(q, shells[i]);
        q = head.push_out(head.off_face(q, sides[i]), shells[i]);
        const Vec3 step = q - p;
        if (length(step) > 1e-12) {
          dir = normalized(step);
          q = p + dir * ds;
        }
      }
      p = q;
      pts.push_back(p);
    }
  }

  // 4: clumps. Centres: a seeded choice of guides; each guide joins the clump whose centre root is nearest.
  std::vector<uint32_t> clump_of(G, 0);
  std::vector<double> clump_phase;
  {
    const uint32_t clumps = std::clamp<uint32_t>(static_cast<uint32_t>(std::lround(G / P.clump_size)), 1u, G);
    std::vector<uint32_t> order(G);
    std::iota(order.begin(), order.end(), 0u);
    for (uint32_t i = G - 1; i > 0; --i) std::swap(order[i], order[rng.below(i + 1)]);
    std::vector<uint32_t> centres(order.begin(), order.begin() + clumps);
    std::sort(centres.begin(), centres.end());
    for (uint32_t c = 0; c < clumps; ++c) clump_phase.push_back(2.0 * kPi * rng.uniform());
    for (uint32_t i = 0; i < G; ++i) {
      double best = std::numeric_limits<double>::infinity();
      for (uint32_t c = 0; c < clumps; ++c) {
        const Vec3 d = roots[i].p - roots[centres[c]].p;
        const double d2 = dot(d, d);
        if (d2 < best) {
          best = d2;
          clump_of[i] = c;
        }
      }
    }
    if (P.clump > 0) {
      std::vector<std::vector<Vec3>> clumped = core;
      for (uint32_t i = 0; i < G; ++i) {
        const std::vector<Vec3>& c = core[centres[clump_of[i]]];
        for (int k = 1; k <= kSteps; ++k) {
          const double s = static_cast<double>(k) / kSteps;
          const double w = P.clump * std::pow(s, 0.8);
          clumped[i][k] = core[i][k] + (c[k] - core[i][k]) * w;
        }
      }
      core.swap(clumped);
    }
  }

  // 5-6: curl and frizz around the core path, then the head pushed out of again.
  RawGroom groom;
  groom.group_names = {"hair"};
  std::vector<Vec3> us, ws, out;
  double total_length = 0.0;
  for (uint32_t i = 0; i < G; ++i) {
    std::vector<Vec3>& pts = core[i];
    transport_frames(pts, us, ws);
    double phase_frizz[6];
    double freq_frizz[6];
    for (int j = 0; j < 6; ++j) {
      phase_frizz[j] = 2.0 * kPi * rng.uniform();
      freq_frizz[j] = (8.0 + 30.0 * rng.uniform()) / std::max(lengths[i], 0.05);
    }
    const double phase = clump_phase[clump_of[i]] + 0.6 * (rng.uniform() - 0.5);
    const double radius = P.curl_radius * (0.8 + 0.4 * rng.uniform());
    out.assign(pts.size(), Vec3{});
    double arc = 0.0;
    for (size_t k = 0; k < pts.size(); ++k) {
      if (k > 0) arc += length(pts[k] - pts[k - 1]);
      const double s = arc / lengths[i];
      Vec3 offset{0, 0, 0};
      if (radius > 0 && P.curl_frequency > 0) {
        const double ease = std::min(1.0, arc / std::max(0.03, 3.0 * radius));
        const double th = 2.0 * kPi * P.curl_frequency * arc + phase;
        // Measured from the helix's start so the root stays where it grew.
        offset = (us[k] * (std::cos(th) - std::cos(phase)) + ws[k] * (std::sin(th) - std::sin(phase))) * (radius * ease);
      }
      if (P.frizz > 0) {
        const double amp = P.frizz * std::pow(s, 1.5);
        double a = 0, b = 0;
        for (int j = 0; j < 3; ++j) a += std::sin(freq_frizz[j] * arc + phase_frizz[j]) / 3.0;
        for (int j = 3; j < 6; ++j) b += std::sin(freq_frizz[j] * arc + phase_frizz[j]) / 3.0;
        offset = offset + (us[k] * a + ws[k] * b) * amp;
      }
      Vec3 q = pts[k] + offset;
      if (k > 0 && head.valid)
        q = head.off_face(head.push_out(head.off_face(q, sides[i]), shells[i] * 0.995), sides[i]);
      out[k] = q;
    }
    out[0] = pts[0];
    double len = 0;
    for (size_t k = 1; k < out.size(); ++k) len += length(out[k] - out[k - 1]);
    total_length += len;
    groom.add_strand(out.data(), out.size(), 0);
  }
  groom.input_vertices = groom.points.size();
  if (report) {
    report->scalp_triangles = static_cast<uint32_t>(tris.size());
    report->scalp_area = total_area;
    report->head_center = center;
    report->head_radius = head.valid ? (radii[0] + radii[1] + radii[2]) / 3.0 : 0.0;
    report->mean_length = total_length / G;
  }
  return groom;
}

asset::HairAsset make_groom(const GroomScalp& scalp, const GroomParams& P, std::string_view preset_name,
                            GroomReport* report) {
  GroomReport rep;
  RawGroom groom = grow_groom(scalp, P, &rep);
  if (!preset_name.empty()) groom.group_names = {std::string(preset_name)};
  BakeOptions o;
  o.vertices_per_strand = P.vertices;
  o.follow_per_guide = P.follow;
  o.seed = P.seed;
  // Follow hairs fill the space between guides: about half the mean root spacing around each guide.
  o.follow_radius = 0.5 * std::sqrt(rep.scalp_area / P.guides);
  o.tip_separation = 0.4f;
  asset::HairAsset a = bake(groom, o);
  char buf[640];
  std::snprintf(buf, sizeof buf,
                ",\"groom\":{\"preset\":\"%.*s\",\"guides\":%u,\"length_m\":%.9g,\"length_variation\":%.9g,"
                "\"parting\":%s%.9g,\"gravity\":%.9g,\"lift\":%.9g,\"clump\":%.9g,\"clump_size\":%.9g,"
                "\"curl_radius_m\":%.9g,\"curl_frequency_per_m\":%.9g,\"frizz_m\":%.9g,\"taper\":%.9g,"
                "\"length_map\":%s}}",
                static_cast<int>(std::min<size_t>(preset_name.size(), 64)), preset_name.data(), P.guides, P.length,
                P.length_variation, P.parting_on ? "" : "null,\"parting_offset\":", P.parting, P.gravity, P.lift,
                P.clump, P.clump_size, P.curl_radius, P.curl_frequency, P.frizz, P.taper,
                scalp.length_map.empty() ? "false" : "true");
  if (!a.bake_settings.empty() && a.bake_settings.back() == '}') {
    a.bake_settings.pop_back();
    a.bake_settings += buf;
  }
  if (report) *report = rep;
  return a;
}

}  // namespace tressvk::baker
