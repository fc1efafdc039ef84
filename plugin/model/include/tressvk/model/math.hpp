// Double-precision vector and quaternion helpers of the CPU reference. Each operation mirrors a function of
// shaders/sim/common.glsl in the same order of operations, so the two differ only by float32 rounding.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

namespace tressvk::model {

struct Vec3 {
  double x = 0, y = 0, z = 0;
  constexpr double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};
constexpr Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
constexpr Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
constexpr Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
constexpr Vec3 operator*(Vec3 a, double s) { return {s * a.x, s * a.y, s * a.z}; }
constexpr Vec3 operator/(Vec3 a, double s) { return {a.x / s, a.y / s, a.z / s}; }
constexpr Vec3& operator+=(Vec3& a, Vec3 b) { return a = a + b; }
constexpr Vec3& operator-=(Vec3& a, Vec3 b) { return a = a - b; }
constexpr double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalize(Vec3 a) { return a / length(a); }
constexpr Vec3 mix(Vec3 a, Vec3 b, double t) { return a + t * (b - a); }
inline bool is_finite(Vec3 a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

// Unit quaternion (x, y, z, w) = (v, w).
struct Quat {
  double x = 0, y = 0, z = 0, w = 1;
  constexpr Vec3 v() const { return {x, y, z}; }
};
constexpr Quat make_quat(Vec3 v, double w) { return {v.x, v.y, v.z, w}; }
inline Quat normalize(Quat q) {
  double n = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  return {q.x / n, q.y / n, q.z / n, q.w / n};
}
constexpr double dot(Quat a, Quat b) { return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w; }
constexpr Quat conjugate(Quat q) { return {-q.x, -q.y, -q.z, q.w}; }
constexpr Quat quat_mul(Quat a, Quat b) {
  return make_quat(a.w * b.v() + b.w * a.v() + cross(a.v(), b.v()), a.w * b.w - dot(a.v(), b.v()));
}
constexpr Vec3 quat_rotate(Quat q, Vec3 v) {
  Vec3 t = 2.0 * cross(q.v(), v);
  return v + q.w * t + cross(q.v(), t);
}
// quat_rotate(q, v) - v without cancellation for small rotations.
constexpr Vec3 quat_rotate_delta(Quat q, Vec3 v) {
  Vec3 t = 2.0 * cross(q.v(), v);
  return q.w * t + cross(q.v(), t);
}
// Minimal rotation taking unit a onto unit b (a half turn about the axis least aligned with a when opposite).
inline Quat quat_from_two_unit(Vec3 a, Vec3 b) {
  double d = dot(a, b);
  if (d < -0.999999) {
    Vec3 axis = std::abs(a.x) < 0.577 ? Vec3{1, 0, 0} : (std::abs(a.y) < 0.577 ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
    return make_quat(normalize(cross(a, axis)), 0.0);
  }
  return normalize(make_quat(cross(a, b), 1.0 + d));
}
// Turns frame q minimally so that its local +X points along edge e (rest length rest_len); an edge shorter than
// its rest length is blended with the frame's +X by the missing length (see frame_align in common.glsl; the
// constants are kCollapse and kDirectionEps there and in model.hpp). The GLSL twin multiplies the rotation in
// unnormalised, (x cross d, |d| + x.d), and normalises the product once: the same frame in exact arithmetic.
inline constexpr double kCollapseAlign = 1.0;  // = kCollapse in model.hpp
// Fold guard (GLSL twin in common.glsl): the amount of unit vector u added to e (length el) so that e never points
// against u; zero within 90 degrees, 2 el cos^2 beyond. Keeps minimal rotations away from half turns.
inline double fold_guard(Vec3 e, double el, Vec3 u) {
  const double eu = dot(e, u);
  return (eu < 0.0 && el > 0.0) ? 2.0 * (eu * eu / el) : 0.0;
}
inline Quat frame_align(Quat q, Vec3 e, double rest_len) {
  const Vec3 x = quat_rotate(q, Vec3{1, 0, 0});
  const double el = length(e);
  const Vec3 d = e + (std::max(kCollapseAlign * rest_len - el, 0.0) + fold_guard(e, el, x)) * x;
  const double len = length(d);
  if (!(len > 1e-4 * rest_len)) return q;
  return normalize(quat_mul(quat_from_two_unit(x, d / len), q));
}
inline Quat slerp(Quat a, Quat b, double t) {
  double d = dot(a, b);
  if (d < 0) {
    b = {-b.x, -b.y, -b.z, -b.w};
    d = -d;
  }
  if (d > 0.9999999) {
    return normalize(Quat{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z), a.w + t * (b.w - a.w)});
  }
  double th = std::acos(std::clamp(d, -1.0, 1.0));
  double s = std::sin(th);
  double wa = std::sin((1 - t) * th) / s, wb = std::sin(t * th) / s;
  return normalize(Quat{wa * a.x + wb * b.x, wa * a.y + wb * b.y, wa * a.z + wb * b.z, wa * a.w + wb * b.w});
}
// Quaternion of a rotation matrix given by rows (m[r][c]).
Quat quat_from_matrix(const std::array<std::array<double, 3>, 3>& m);
std::array<std::array<double, 3>, 3> matrix_from_quat(Quat q);

}  // namespace tressvk::model
