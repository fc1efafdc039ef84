// Root orientation against a scalp mesh, and loading the scalp's faces.
#include "vec_math.hpp"

#include <tressvk/baker/errors.hpp>
#include <tressvk/baker/import.hpp>

#include <algorithm>
#include <limits>

namespace tressvk::baker {
namespace {

// Squared distance from p to triangle abc: project onto the plane when the projection is inside, otherwise
// the nearest of the three edges (each as a clamped segment).
double distance_sq_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double l2 = dot(ab, ab);
  const double t = l2 > 0 ? std::clamp(dot(p - a, ab) / l2, 0.0, 1.0) : 0.0;
  const Vec3 d = p - (a + ab * t);
  return dot(d, d);
}

double distance_sq_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = cross(b - a, c - a);
  const double n2 = dot(n, n);
  if (n2 > 0) {
    const double s = dot(p - a, n) / n2;
    const Vec3 q = p - n * s;  // projection onto the plane
    // Inside test: q is on the same side of all three edges.
    const bool inside = dot(cross(b - a, q - a), n) >= 0 && dot(cross(c - b, q - b), n) >= 0 &&
                        dot(cross(a - c, q - c), n) >= 0;
    if (inside) return s * s * n2;
  }
  return std::min({distance_sq_to_segment(p, a, b), distance_sq_to_segment(p, b, c), distance_sq_to_segment(p, c, a)});
}

double distance_sq_to_mesh(const Vec3& p, const ScalpMesh& m) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : m.triangles)
    best = std::min(best, distance_sq_to_triangle(p, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]));
  return best;
}

}  // namespace

void orient_to_scalp(RawGroom& groom, const ScalpMesh& scalp) {
  for (size_t s = 0; s < groom.strand_count(); ++s) {
    auto first = groom.points.begin() + groom.strand_begin[s];
    auto last = groom.points.begin() + groom.strand_begin[s + 1];
    if (distance_sq_to_mesh(*(last - 1), scalp) < distance_sq_to_mesh(*first, scalp)) std::reverse(first, last);
  }
}

ScalpMesh load_scalp(const std::filesystem::path& path) {
  const auto bytes = read_binary_file(path);
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  ScalpMesh mesh;
  import_obj_text(text, path.string(), {}, &mesh);
  if (mesh.triangles.empty()) throw InputError(path.string() + ": the scalp file has no faces");
  return mesh;
}

}  // namespace tressvk::baker
