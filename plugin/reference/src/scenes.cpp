#include "tressvk/reference/scenes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace tressvk::reference {
namespace {

constexpr double kPi = std::numbers::pi;

Quat axis_angle(Vec3 axis, double angle) {
  return make_quat(std::sin(0.5 * angle) * normalize(axis), std::cos(0.5 * angle));
}

// Solves the 4x4 system m * x = r by Gaussian elimination with partial pivoting; false when singular.
bool solve4(std::array<std::array<double, 5>, 4> m, std::array<double, 4>& x) {
  for (size_t c = 0; c < 4; ++c) {
    size_t piv = c;
    for (size_t r = c + 1; r < 4; ++r) {
      if (std::abs(m[r][c]) > std::abs(m[piv][c])) piv = r;
    }
    if (std::abs(m[piv][c]) < 1e-14) return false;
    std::swap(m[c], m[piv]);
    for (size_t r = 0; r < 4; ++r) {
      if (r == c) continue;
      double f = m[r][c] / m[c][c];
      for (size_t k = c; k < 5; ++k) m[r][k] -= f * m[c][k];
    }
  }
  for (size_t c = 0; c < 4; ++c) x[c] = m[c][4] / m[c][c];
  return true;
}

// Places the instance so that the head centre is the pivot of rotation q, then adds offset.
TvkInstanceTransform pose_about(const SceneGeometry& geo, Quat q, Vec3 offset) {
  const Vec3 c = geo.head_centre;
  // Translations are quantised to 2^-30 m (about 1 nm) so that adding the far scene's 10 km is exact in double:
  // far and shake then receive the same motion to the last bit and differ only by what the simulation does.
  auto quantise = [](double x) { return std::ldexp(std::round(std::ldexp(x, 30)), -30); };
  Vec3 t = (c - quat_rotate(q, c)) + offset;
  t = {quantise(t.x), quantise(t.y), quantise(t.z)};
  TvkInstanceTransform x = TVK_INSTANCE_TRANSFORM_DEFAULT_INIT;
  x.translation[0] = t.x;
  x.translation[1] = t.y;
  x.translation[2] = t.z;
  x.rotation[0] = q.x;
  x.rotation[1] = q.y;
  x.rotation[2] = q.z;
  x.rotation[3] = q.w;
  return x;
}

void set_capsule(TvkCapsule& cap, Vec3 p0, double r0, Vec3 p1, double r1) {
  cap.p0[0] = static_cast<float>(p0.x);
  cap.p0[1] = static_cast<float>(p0.y);
  cap.p0[2] = static_cast<float>(p0.z);
  cap.p1[0] = static_cast<float>(p1.x);
  cap.p1[1] = static_cast<float>(p1.y);
  cap.p1[2] = static_cast<float>(p1.z);
  cap.r0 = static_cast<float>(r0);
  cap.r1 = static_cast<float>(r1);
}

}  // namespace

SceneGeometry scene_geometry(const ModelRest& rest) {
  const uint32_t n = rest.vertices_per_strand;
  const Vec3 origin{rest.asset_origin[0], rest.asset_origin[1], rest.asset_origin[2]};
  std::vector<Vec3> roots;
  for (uint32_t g = 0; g < rest.guide_count; ++g) roots.push_back(rest.rest_pos[size_t{g} * n]);
  SceneGeometry geo;
  if (roots.empty()) return geo;
  Vec3 mean, lo = roots[0], hi = roots[0];
  for (const Vec3& r : roots) {
    mean += r;
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], r[k]);
      hi[k] = std::max(hi[k], r[k]);
    }
  }
  mean = mean / static_cast<double>(roots.size());
  const double half_diag = 0.5 * length(hi - lo);

  // |x|^2 = 2 c.x + k, on centred points, in the least-squares sense.
  std::array<std::array<double, 5>, 4> m{};
  for (const Vec3& r : roots) {
    const Vec3 x = r - mean;
    const std::array<double, 4> row{2 * x.x, 2 * x.y, 2 * x.z, 1.0};
    const double rhs = dot(x, x);
    for (size_t i = 0; i < 4; ++i) {
      for (size_t j = 0; j < 4; ++j) m[i][j] += row[i] * row[j];
      m[i][4] += row[i] * rhs;
    }
  }
  std::array<double, 4> sol{};
  bool fitted = false;
  if (solve4(m, sol)) {
    const Vec3 c{sol[0], sol[1], sol[2]};
    const double r2 = sol[3] + dot(c, c);
    if (r2 > 0) {
      const double r = std::sqrt(r2);
      double dev = 0;
      for (const Vec3& p : roots) dev += std::abs(length(p - mean - c) - r);
      dev /= static_cast<double>(roots.size());
      // Only a clean sphere that the roots cover broadly (a scalp, not a strip on a big arc).
      if (dev < 0.02 * r && r < 1.2 * half_diag && r > 0.3 * half_diag) {
        geo.head_centre = origin + mean + c;
        geo.head_radius = r;
        fitted = true;
      }
    }
  }
  if (!fitted) {
    // The point nearest (least squares) to the lines through each root along its root edge: where the hair
    // directions converge, i.e. inside the head or body the roots sit on.
    std::array<std::array<double, 5>, 4> a{};
    a[3][3] = 1.0;  // a 3x3 system embedded in the 4x4 solver
    for (uint32_t g = 0; g < rest.guide_count; ++g) {
      const Vec3 r = rest.rest_pos[size_t{g} * n];
      const Vec3 e = rest.rest_pos[size_t{g} * n + 1] - r;
      const double l = length(e);
      if (!(l > 0)) continue;
      const Vec3 d = e / l;
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          const double proj = (i == j ? 1.0 : 0.0) - d[i] * d[j];
          a[static_cast<size_t>(i)][static_cast<size_t>(j)] += proj;
          a[static_cast<size_t>(i)][4] += proj * r[j];
        }
      }
    }
    std::array<double, 4> x{};
    if (solve4(a, x)) {
      const Vec3 c{x[0], x[1], x[2]};
      double r = 0;
      for (const Vec3& p : roots) r += length(p - c);
      r /= static_cast<double>(roots.size());
      if (r > 0.1 * half_diag && r < 3.0 * half_diag) {
        geo.head_centre = origin + c;
        geo.head_radius = r;
        fitted = true;
      }
    }
  }
  if (!fitted) {
    const double radius = std::max(0.5 * std::max(hi.x - lo.x, hi.z - lo.z), 1e-3);
    geo.head_centre = origin + mean - Vec3{0, radius, 0};
    geo.head_radius = radius;
  }
  // The head collider sits inside the scalp: 90% of the distance of the nearest tenth of the roots.
  std::vector<double> dist;
  for (const Vec3& p : roots) dist.push_back(length(origin + p - geo.head_centre));
  auto tenth = dist.begin() + static_cast<std::ptrdiff_t>(dist.size() / 10);
  std::nth_element(dist.begin(), tenth, dist.end());
  geo.inner_radius = 0.9 * *tenth;
  return geo;
}

std::vector<std::string> scene_names() { return {"settle", "shake", "run", "teleport", "wind", "hitch", "far"}; }

TvkSimFrame scene_frame(std::string_view name, uint32_t frame_index, const SceneGeometry& geo) {
  TvkSimFrame f{};
  f.dt = static_cast<float>(kSceneFrameDt);
  f.transform = TVK_INSTANCE_TRANSFORM_DEFAULT_INIT;
  f.wind = TVK_WIND_DEFAULT_INIT;
  const double t = static_cast<double>(frame_index + 1) * kSceneFrameDt;  // time at the end of the frame
  const Vec3 up{0, 1, 0};
  const double r = geo.head_radius;

  if (name == "settle") {
    f.transform = pose_about(geo, Quat{}, Vec3{});
  } else if (name == "shake" || name == "far") {
    const double angle = (kPi / 3.0) * std::sin(2.0 * kPi * 2.0 * t);
    f.transform = pose_about(geo, axis_angle(up, angle), name == "far" ? Vec3{kFarDistance, 0, 0} : Vec3{});
  } else if (name == "run") {
    const double phase = 2.0 * kPi * 2.8 * t;
    const Quat nod = axis_angle(Vec3{1, 0, 0}, (8.0 * kPi / 180.0) * std::sin(phase + 0.5));
    f.transform = pose_about(geo, nod, Vec3{0, 0.04 * std::sin(phase), 3.0 * t});
    const Vec3 c = geo.head_centre;
    f.capsule_count = 2;
    set_capsule(f.capsules[0], c - 0.25 * r * up, geo.inner_radius, c, geo.inner_radius);
    set_capsule(f.capsules[1], c + Vec3{-3.0 * r, -2.8 * r, 0}, 0.6 * r, c + Vec3{3.0 * r, -2.8 * r, 0}, 0.6 * r);
  } else if (name == "teleport") {
    const uint32_t k = frame_index / 60;
    f.transform = pose_about(geo, axis_angle(up, 0.5 * kPi * static_cast<double>(k)),
                             Vec3{static_cast<double>(k), 0, 0});
    f.teleport = (frame_index % 60 == 0 && frame_index > 0) ? 1u : 0u;
  } else if (name == "wind") {
    f.transform = pose_about(geo, Quat{}, Vec3{});
    f.wind.direction[0] = 1.0f;
    f.wind.direction[1] = 0.0f;
    f.wind.direction[2] = 0.3f;
    f.wind.strength = 4.0f;
    f.wind.gust_amplitude = 0.8f;
    f.wind.gust_frequency = 0.5f;
  } else if (name == "hitch") {
    const bool long_frame = frame_index % 2 == 1;
    f.dt = long_frame ? 0.25f : static_cast<float>(kSceneFrameDt);
    // Time at the end of this frame: (i/2 + 1) short frames and (i+1)/2 long ones so far.
    const double th = static_cast<double>(frame_index / 2 + 1) * static_cast<double>(static_cast<float>(kSceneFrameDt)) +
                      static_cast<double>((frame_index + 1) / 2) * 0.25;
    const double angle = (kPi / 3.0) * std::sin(2.0 * kPi * 0.7 * th);
    f.transform = pose_about(geo, axis_angle(up, angle), Vec3{0, 0, 1.5 * th});
  } else {
    throw std::invalid_argument("unknown scene '" + std::string(name) + "' (settle, shake, run, teleport, wind, hitch, far)");
  }
  return f;
}

std::vector<TvkBoneMatrix> rocking_bones(uint32_t bone_count, const std::array<double, 3>& origin,
                                         uint32_t frame_index, const SceneGeometry& geometry) {
  // The pivot is the head centre expressed in bind space (the asset's positions are relative to its origin).
  const Vec3 c = geometry.head_centre + Vec3{origin[0], origin[1], origin[2]};
  std::vector<TvkBoneMatrix> matrices(bone_count);
  for (uint32_t b = 0; b < bone_count; ++b) {
    const double angle = 0.15 * std::sin(2.0 * std::numbers::pi * 1.5 * frame_index * kSceneFrameDt + 0.37 * b);
    const double cs = std::cos(angle), sn = std::sin(angle);
    // Rotation about Y through c: x' = R (x - c) + c.
    const double r[3][3] = {{cs, 0, sn}, {0, 1, 0}, {-sn, 0, cs}};
    for (int i = 0; i < 3; ++i) {
      double t = c[i];
      for (int j = 0; j < 3; ++j) {
        matrices[b].rows[i][j] = static_cast<float>(r[i][j]);
        t -= r[i][j] * c[j];
      }
      matrices[b].rows[i][3] = static_cast<float>(t);
    }
  }
  return matrices;
}

}  // namespace tressvk::reference
