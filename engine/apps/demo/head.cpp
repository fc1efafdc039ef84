// The sample head (see head.hpp): a latitude-longitude surface around the head's middle whose radius is an
// ellipsoid (longer below the eyes, the jaw narrowing) plus smooth bumps and dents for the face, with ears, eyes,
// neck and shoulders as separate closed shapes.
#include "head.hpp"

#include <tressvk/asset_io.hpp>
#include <tressvk/engine/check.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace tressvk::demo {
namespace {

constexpr double kPi = 3.14159265358979323846;
using D3 = std::array<double, 3>;

D3 add(const D3& a, const D3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
D3 sub(const D3& a, const D3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
D3 mul(const D3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
D3 cross(const D3& a, const D3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const D3& a, const D3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
D3 normalize(const D3& a) {
  const double l = std::sqrt(dot(a, a));
  return l > 0 ? mul(a, 1.0 / l) : D3{0, 1, 0};
}
double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}
double bump(double dx, double dy, double cx, double cy, double sx, double sy) {
  const double u = (dx - cx) / sx, v = (dy - cy) / sy;
  return std::exp(-(u * u + v * v));
}

// The head's radius along unit direction d (x right of the viewer looking at the face = the head's left, y up,
// z out of the face).
double head_radius(const D3& d) {
  const double dx = d[0], dy = d[1], dz = d[2];
  // Cranium and jaw: an ellipsoid, taller below the eyes, narrower and shallower towards the chin.
  const double below = smoothstep(-0.05, -0.85, dy);
  const double ax = 0.077 * (1.0 - 0.30 * below);
  const double ay = dy > 0 ? 0.108 : 0.128;
  const double az = (dz > 0 ? 0.093 : 0.102) * (1.0 - (dz < 0 ? 0.35 : 0.05) * below);
  double r = 1.0 / std::sqrt(dx * dx / (ax * ax) + dy * dy / (ay * ay) + dz * dz / (az * az));
  // Face features live on the front.
  const double front = smoothstep(0.35, 0.75, dz);
  if (front <= 0) return r;
  double f = 0;
  // Brow ridge and forehead.
  f += 0.0045 * bump(dx, dy, 0, 0.17, 0.55, 0.06);
  // Eye sockets.
  f -= 0.013 * bump(dx, dy, 0.30, 0.06, 0.14, 0.09);
  f -= 0.013 * bump(dx, dy, -0.30, 0.06, 0.14, 0.09);
  // Nose: a ridge from the bridge down to the tip, wider and higher towards the tip, then the nostrils.
  {
    const double t = std::clamp((0.06 - dy) / 0.33, 0.0, 1.0);
    const double h = 0.003 + 0.021 * std::pow(t, 1.4);
    const double sx = 0.045 + 0.05 * t;
    double along = 1.0;
    if (dy > 0.06) along = std::exp(-std::pow((dy - 0.06) / 0.05, 2));
    if (dy < -0.27) along = std::exp(-std::pow((dy + 0.27) / 0.035, 2));
    f += h * along * std::exp(-std::pow(dx / sx, 2));
    f += 0.006 * bump(dx, dy, 0.095, -0.25, 0.05, 0.04);
    f += 0.006 * bump(dx, dy, -0.095, -0.25, 0.05, 0.04);
  }
  // Cheekbones.
  f += 0.005 * bump(dx, dy, 0.42, -0.12, 0.13, 0.1);
  f += 0.005 * bump(dx, dy, -0.42, -0.12, 0.13, 0.1);
  // Lips and the line between them, then the chin.
  f += 0.008 * bump(dx, dy, 0, -0.41, 0.17, 0.045);
  f += 0.007 * bump(dx, dy, 0, -0.52, 0.14, 0.045);
  f -= 0.004 * bump(dx, dy, 0, -0.465, 0.17, 0.016);
  f += 0.008 * bump(dx, dy, 0, -0.72, 0.16, 0.08);
  return r + front * f;
}

D3 direction(double theta, double phi) {  // theta from +Y, phi from +Z towards +X
  return {std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi)};
}

// The hairline: hair grows where the direction's y is above this (front high, back low), not around the ears.
double hairline(const D3& d) {
  const double phi = std::atan2(d[0], d[2]);
  return -0.55 + 0.97 * std::pow(0.5 * (1.0 + std::cos(phi)), 1.2);
}
bool by_ear(const D3& d) { return std::abs(d[0]) > 0.8 && d[1] < 0.22 && std::abs(d[2] + 0.05) < 0.32; }
bool in_hair_region(const D3& d) { return d[1] > hairline(d) && !by_ear(d); }
// The scalp's paint (hair-root colour under the hair), fading out just inside the hairline.
float scalp_paint(const D3& d) {
  if (by_ear(d)) return 0.0f;
  return static_cast<float>(0.85 * smoothstep(0.04, 0.2, d[1] - hairline(d)));
}

engine::MeshVertex vertex(const D3& p, const D3& n) {
  engine::MeshVertex v{};
  for (int i = 0; i < 3; ++i) {
    v.position[i] = static_cast<float>(p[i]);
    v.normal[i] = static_cast<float>(n[i]);
  }
  v.position[3] = 1.0f;
  return v;
}

// An indexed grid surface -> flat triangles with smooth normals, every triangle wound counter-clockwise seen
// from outside (outside = away from `inside`).
void emit(const std::vector<D3>& pts, const std::vector<std::array<uint32_t, 3>>& tris, const D3& inside,
          engine::Mesh& out) {
  std::vector<D3> normals(pts.size(), D3{0, 0, 0});
  std::vector<std::array<uint32_t, 3>> wound;
  for (auto t : tris) {
    D3 n = cross(sub(pts[t[1]], pts[t[0]]), sub(pts[t[2]], pts[t[0]]));
    if (dot(n, n) <= 0) continue;
    if (dot(n, sub(pts[t[0]], inside)) < 0) {
      std::swap(t[1], t[2]);
      n = mul(n, -1.0);
    }
    wound.push_back(t);
    for (uint32_t i : t) normals[i] = add(normals[i], n);
  }
  for (const auto& t : wound)
    for (uint32_t i : t) out.vertices.push_back(vertex(pts[i], normalize(normals[i])));
}

// A closed lat-long surface: point(theta, phi) for theta 0..pi, phi 0..2pi.
template <typename F>
void surface(uint32_t rings, uint32_t segments, const D3& inside, F&& point, engine::Mesh& out,
             std::vector<D3>* pts_out = nullptr, std::vector<std::array<uint32_t, 3>>* tris_out = nullptr) {
  std::vector<D3> pts;
  std::vector<std::array<uint32_t, 3>> tris;
  for (uint32_t i = 0; i <= rings; ++i)
    for (uint32_t j = 0; j < segments; ++j)
      pts.push_back(point(kPi * i / rings, 2.0 * kPi * j / segments));
  for (uint32_t i = 0; i < rings; ++i)
    for (uint32_t j = 0; j < segments; ++j) {
      const uint32_t a = i * segments + j, b = i * segments + (j + 1) % segments;
      const uint32_t c = a + segments, e = b + segments;
      tris.push_back({a, c, b});
      tris.push_back({b, c, e});
    }
  emit(pts, tris, inside, out);
  if (pts_out) *pts_out = std::move(pts);
  if (tris_out) *tris_out = std::move(tris);
}

void ellipsoid(const D3& c, const D3& r, double yaw, engine::Mesh& out, uint32_t rings = 16, uint32_t segs = 24) {
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  surface(rings, segs, c,
          [&](double th, double ph) {
            const D3 d = direction(th, ph);
            const D3 l{d[0] * r[0], d[1] * r[1], d[2] * r[2]};
            return add(c, D3{cy * l[0] + sy * l[2], l[1], -sy * l[0] + cy * l[2]});
          },
          out);
}

TvkCapsule capsule(const D3& p0, double r0, const D3& p1, double r1) {
  TvkCapsule c{};
  for (int i = 0; i < 3; ++i) {
    c.p0[i] = static_cast<float>(p0[i]);
    c.p1[i] = static_cast<float>(p1[i]);
  }
  c.r0 = static_cast<float>(r0);
  c.r1 = static_cast<float>(r1);
  return c;
}

std::array<float, 3> f3(const D3& p) {
  return {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])};
}

}  // namespace

SampleHead make_sample_head() {
  SampleHead h;
  // The head surface, and the scalp cut from it (the same vertices, so roots sit exactly on the skin).
  std::vector<D3> pts;
  std::vector<std::array<uint32_t, 3>> tris;
  const D3 origin{0, 0, 0};
  surface(128, 176, origin, [](double th, double ph) {
    const D3 d = direction(th, ph);
    return mul(d, head_radius(d));
  }, h.skin, &pts, &tris);
  for (engine::MeshVertex& v : h.skin.vertices)
    v.normal[3] = scalp_paint(normalize(D3{v.position[0], v.position[1], v.position[2]}));
  {
    std::vector<int64_t> remap(pts.size(), -1);
    for (const auto& t : tris) {
      bool all = true;
      for (uint32_t i : t) all = all && in_hair_region(normalize(pts[i]));
      if (!all) continue;
      std::array<uint32_t, 3> st{};
      for (int k = 0; k < 3; ++k) {
        if (remap[t[k]] < 0) {
          remap[t[k]] = static_cast<int64_t>(h.scalp.vertices.size());
          h.scalp.vertices.push_back(pts[t[k]]);
          // Length map: the front (fringe) a little shorter so it frames the face, full length behind.
          const D3 d = normalize(pts[t[k]]);
          h.scalp.length_map.push_back(0.82 + 0.18 * (1.0 - smoothstep(0.2, 0.9, d[2])));
        }
        st[k] = static_cast<uint32_t>(remap[t[k]]);
      }
      // Outward winding (the groom generator orients normals itself, but keep the file tidy).
      const D3 n = cross(sub(h.scalp.vertices[st[1]], h.scalp.vertices[st[0]]),
                         sub(h.scalp.vertices[st[2]], h.scalp.vertices[st[0]]));
      if (dot(n, h.scalp.vertices[st[0]]) < 0) std::swap(st[1], st[2]);
      h.scalp.triangles.push_back(st);
    }
  }
  auto on_face = [](double dx, double dy, double inset) {
    const D3 d = normalize(D3{dx, dy, std::sqrt(std::max(0.0, 1.0 - dx * dx - dy * dy))});
    return mul(d, head_radius(d) - inset);
  };
  // Eyes: balls in the sockets.
  const double eye_r = 0.0118;
  const D3 le = on_face(0.30, 0.06, 0.0035 - eye_r + 0.0005), re = on_face(-0.30, 0.06, 0.0035 - eye_r + 0.0005);
  const D3 left_eye_c = sub(le, mul(normalize(le), eye_r)), right_eye_c = sub(re, mul(normalize(re), eye_r));
  ellipsoid(left_eye_c, {eye_r, eye_r, eye_r}, 0, h.eyes, 16, 24);
  ellipsoid(right_eye_c, {eye_r, eye_r, eye_r}, 0, h.eyes, 16, 24);
  h.left_eye = f3(le);
  h.right_eye = f3(re);
  h.nose_tip = f3(on_face(0.0, -0.27, 0.0));
  h.mouth = f3(on_face(0.0, -0.465, 0.0));
  h.chin = f3(on_face(0.0, -0.72, 0.0));
  h.brow = f3(on_face(0.0, 0.17, 0.0));
  // Ears: flattened ellipsoids against the sides, turned a little to face forward, with a rim.
  for (double side : {1.0, -1.0}) {
    const D3 c{side * 0.079, -0.004, -0.012};
    ellipsoid(c, {0.009, 0.029, 0.018}, side * 0.25, h.skin);
    ellipsoid(add(c, D3{side * 0.004, 0.004, -0.003}), {0.006, 0.024, 0.014}, side * 0.25, h.skin);
  }
  // Neck, shoulders and chest.
  const D3 neck0{0, -0.07, -0.018}, neck1{0, -0.21, -0.025};
  h.skin.append(engine::make_capsule_mesh(f3(neck0), 0.052f, f3(neck1), 0.058f, 32, 16));
  // Shoulders and upper chest: one flattened ellipsoid, so they round off like shoulders.
  ellipsoid({0, -0.3, -0.03}, {0.18, 0.1, 0.095}, 0, h.skin, 32, 48);
  const D3 sl{-0.13, -0.29, -0.03}, sr{0.13, -0.29, -0.03};
  const D3 chest0{0, -0.3, -0.03}, chest1{0, -0.4, -0.03};

  // Colliders, a few millimetres inside what they stand for: cranium (front to back), face and jaw, neck,
  // shoulders, chest.
  h.colliders.push_back(capsule({0, 0.012, 0.015}, 0.072, {0, 0.012, -0.03}, 0.072));
  h.colliders.push_back(capsule({0, -0.03, 0.025}, 0.062, {0, -0.075, 0.02}, 0.05));
  h.colliders.push_back(capsule(neck0, 0.049, neck1, 0.055));
  h.colliders.push_back(capsule(sl, 0.058, sr, 0.058));
  h.colliders.push_back(capsule(chest0, 0.085, chest1, 0.09));
  return h;
}

void export_sample_head(const SampleHead& head, const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw engine::Error(dir.string() + ": cannot create the directory: " + ec.message());
  std::string obj = "# tressvk sample head: metres, +Y up, face towards +Z (generated by tressvk-demo)\n";
  char buf[160];
  auto write_mesh = [&](const engine::Mesh& m, const char* name, size_t& base) {
    obj += std::string("o ") + name + "\n";
    for (const auto& v : m.vertices) {
      std::snprintf(buf, sizeof buf, "v %.7g %.7g %.7g\nvn %.6g %.6g %.6g\n", v.position[0], v.position[1],
                    v.position[2], v.normal[0], v.normal[1], v.normal[2]);
      obj += buf;
    }
    for (size_t i = 0; i + 2 < m.vertices.size(); i += 3) {
      const size_t a = base + i + 1;
      std::snprintf(buf, sizeof buf, "f %zu//%zu %zu//%zu %zu//%zu\n", a, a, a + 1, a + 1, a + 2, a + 2);
      obj += buf;
    }
    base += m.vertices.size();
  };
  size_t base = 0;
  write_mesh(head.skin, "skin", base);
  write_mesh(head.eyes, "eyes", base);
  for (const auto& [name, text] : {std::pair<std::string, std::string>{"head.obj", obj},
                                   std::pair<std::string, std::string>{"scalp.obj", baker::groom_scalp_obj(head.scalp)}}) {
    const auto err = asset::write_file(dir / name, std::as_bytes(std::span(text.data(), text.size())));
    if (!err.empty()) throw engine::Error(err);
  }
}

}  // namespace tressvk::demo
