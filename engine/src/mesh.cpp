#include <tressvk/engine/check.hpp>
#include <tressvk/engine/mesh.hpp>

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace tressvk::engine {

namespace {

using V3 = std::array<double, 3>;
V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
V3 normalize(const V3& a) {
  const double l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  return l > 0 ? V3{a[0] / l, a[1] / l, a[2] / l} : V3{0, 1, 0};
}
MeshVertex vertex(const V3& p, const V3& n) {
  return {{static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2]), 1.0f},
          {static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2]), 0.0f}};
}

}  // namespace

MeshBounds mesh_bounds(const Mesh& mesh) {
  MeshBounds b;
  b.min.fill(std::numeric_limits<double>::max());
  b.max.fill(std::numeric_limits<double>::lowest());
  for (const MeshVertex& v : mesh.vertices)
    for (int i = 0; i < 3; ++i) {
      b.min[i] = std::min<double>(b.min[i], v.position[i]);
      b.max[i] = std::max<double>(b.max[i], v.position[i]);
    }
  return b;
}

Mesh make_capsule_mesh(const std::array<float, 3>& p0f, float r0, const std::array<float, 3>& p1f, float r1,
                       uint32_t segments, uint32_t rings) {
  // A latitude-longitude grid around the axis: the first half of the rings is the hemisphere at p0, the second
  // half the one at p1; the band between them is the tapered body.
  constexpr double kPi = 3.14159265358979323846;
  const V3 p0{p0f[0], p0f[1], p0f[2]}, p1{p1f[0], p1f[1], p1f[2]};
  V3 axis = sub(p1, p0);
  const bool sphere = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]) < 1e-9;
  axis = sphere ? V3{0, 1, 0} : normalize(axis);
  const V3 helper = std::abs(axis[1]) < 0.9 ? V3{0, 1, 0} : V3{1, 0, 0};
  const V3 u = normalize(cross(helper, axis));
  const V3 w = cross(axis, u);
  const uint32_t half = std::max(2u, rings / 2);
  const auto point = [&](uint32_t ring, uint32_t seg) {
    // ring 0..2*half: polar angle from -axis (at p0) to +axis (at p1)
    const bool second = ring > half;
    const double polar = kPi * static_cast<double>(ring) / (2.0 * half);  // 0..pi
    const double phi = 2.0 * kPi * static_cast<double>(seg) / segments;
    const double s = std::sin(polar), c = -std::cos(polar);
    const V3 n{axis[0] * c + (u[0] * std::cos(phi) + w[0] * std::sin(phi)) * s,
               axis[1] * c + (u[1] * std::cos(phi) + w[1] * std::sin(phi)) * s,
               axis[2] * c + (u[2] * std::cos(phi) + w[2] * std::sin(phi)) * s};
    const V3& centre = second ? p1 : p0;
    const double r = second ? r1 : r0;
    return vertex({centre[0] + n[0] * r, centre[1] + n[1] * r, centre[2] + n[2] * r}, n);
  };
  Mesh mesh;
  for (uint32_t ring = 0; ring < 2 * half; ++ring) {
    for (uint32_t seg = 0; seg < segments; ++seg) {
      const MeshVertex a = point(ring, seg), b = point(ring, seg + 1), c = point(ring + 1, seg + 1),
                       d = point(ring + 1, seg);
      mesh.vertices.insert(mesh.vertices.end(), {a, c, b, a, d, c});
    }
  }
  return mesh;
}

Mesh make_floor_mesh(const std::array<float, 3>& c, float h) {
  const V3 n{0, 1, 0};
  const MeshVertex a = vertex({c[0] - h, c[1], c[2] - h}, n), b = vertex({c[0] + h, c[1], c[2] - h}, n),
                   d = vertex({c[0] + h, c[1], c[2] + h}, n), e = vertex({c[0] - h, c[1], c[2] + h}, n);
  Mesh mesh;
  mesh.vertices = {a, e, d, a, d, b};
  return mesh;
}

Mesh load_obj_mesh(const std::filesystem::path& path) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path.string(), config))
    throw Error(path.string() + ": cannot load OBJ mesh: " + reader.Error());
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  Mesh mesh;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const auto& idx = shape.mesh.indices;
    for (size_t f = 0; f + 2 < idx.size(); f += 3) {
      V3 p[3];
      for (size_t k = 0; k < 3; ++k) {
        const int vi = idx[f + k].vertex_index;
        if (vi < 0 || static_cast<size_t>(3 * vi + 2) >= attrib.vertices.size())
          throw Error(path.string() + ": shape '" + shape.name + "': face " + std::to_string(f / 3 + 1) +
                      " refers to a missing vertex");
        p[k] = {attrib.vertices[3 * static_cast<size_t>(vi)], attrib.vertices[3 * static_cast<size_t>(vi) + 1],
                attrib.vertices[3 * static_cast<size_t>(vi) + 2]};
      }
      const V3 face_n = normalize(cross(sub(p[1], p[0]), sub(p[2], p[0])));
      for (size_t k = 0; k < 3; ++k) {
        V3 n = face_n;
        const int ni = idx[f + k].normal_index;
        if (ni >= 0 && static_cast<size_t>(3 * ni + 2) < attrib.normals.size())
          n = normalize({attrib.normals[3 * static_cast<size_t>(ni)], attrib.normals[3 * static_cast<size_t>(ni) + 1],
                         attrib.normals[3 * static_cast<size_t>(ni) + 2]});
        mesh.vertices.push_back(vertex(p[k], n));
      }
    }
  }
  if (mesh.vertices.empty()) throw Error(path.string() + ": the OBJ file has no triangles");
  if (!reader.Warning().empty()) std::fprintf(stderr, "%s: %s", path.string().c_str(), reader.Warning().c_str());
  return mesh;
}

}  // namespace tressvk::engine
