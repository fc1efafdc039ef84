// Small double-precision vector and quaternion helpers for the bake pipeline (offline math stays in double).
#pragma once

#include <tressvk/baker/raw_groom.hpp>

#include <cmath>

namespace tressvk::baker {

struct Quat {
  double x = 0, y = 0, z = 0, w = 1;
};

inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3 operator*(const Vec3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double length(const Vec3& a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalized(const Vec3& a) {
  const double l = length(a);
  return l > 0 ? a * (1.0 / l) : Vec3{0, 0, 0};
}

inline Quat operator*(const Quat& a, const Quat& b) {
  return {a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
          a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}
inline Quat conjugate(const Quat& q) { return {-q.x, -q.y, -q.z, q.w}; }
inline Quat normalized(const Quat& q) {
  const double l = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  return {q.x / l, q.y / l, q.z / l, q.w / l};
}
inline Vec3 rotate(const Quat& q, const Vec3& v) {
  const Vec3 u{q.x, q.y, q.z};
  const Vec3 t = cross(u, v) * 2.0;
  return v + t * q.w + cross(u, t);
}

// Rotation matrix with the given orthonormal columns -> quaternion (Shepperd's method: pick the largest term).
inline Quat quat_from_axes(const Vec3& x, const Vec3& y, const Vec3& z) {
  const double m00 = x[0], m10 = x[1], m20 = x[2], m01 = y[0], m11 = y[1], m21 = y[2], m02 = z[0], m12 = z[1],
               m22 = z[2];
  const double tr = m00 + m11 + m22;
  Quat q;
  if (tr > 0) {
    const double s = std::sqrt(tr + 1.0) * 2;
    q = {(m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s, 0.25 * s};
  } else if (m00 > m11 && m00 > m22) {
    const double s = std::sqrt(1.0 + m00 - m11 - m22) * 2;
    q = {0.25 * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s};
  } else if (m11 > m22) {
    const double s = std::sqrt(1.0 + m11 - m00 - m22) * 2;
    q = {(m01 + m10) / s, 0.25 * s, (m12 + m21) / s, (m02 - m20) / s};
  } else {
    const double s = std::sqrt(1.0 + m22 - m00 - m11) * 2;
    q = {(m02 + m20) / s, (m12 + m21) / s, 0.25 * s, (m10 - m01) / s};
  }
  return normalized(q);
}

// The minimal rotation taking unit vector a onto unit vector b. For opposite vectors it turns by pi about an
// axis perpendicular to a (any such axis is minimal).
inline Quat rotation_between(const Vec3& a, const Vec3& b) {
  const double d = dot(a, b);
  if (d < -1.0 + 1e-12) {
    Vec3 axis = cross(a, Vec3{1, 0, 0});
    if (dot(axis, axis) < 1e-6) axis = cross(a, Vec3{0, 1, 0});
    axis = normalized(axis);
    return {axis[0], axis[1], axis[2], 0.0};
  }
  const Vec3 c = cross(a, b);
  return normalized(Quat{c[0], c[1], c[2], 1.0 + d});
}

// Deterministic random numbers (SplitMix64): the same on every platform and standard library, unlike
// std::uniform_real_distribution.
class Random {
 public:
  explicit Random(uint64_t seed) : state_(seed) {}
  uint64_t next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  uint64_t below(uint64_t n) { return n ? next() % n : 0; }  // modulo bias < n / 2^64: irrelevant here

 private:
  uint64_t state_;
};

}  // namespace tressvk::baker
