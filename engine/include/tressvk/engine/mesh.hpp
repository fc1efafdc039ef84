// Triangle meshes for the host scene: procedural capsules, spheres and planes (the bundled sample head needs no
// file), and OBJ loading (tinyobjloader). Meshes are flat triangle lists drawn from a storage buffer with
// gl_VertexIndex (the engine uses no vertex buffers).
#pragma once

#include <array>
#include <filesystem>
#include <vector>

namespace tressvk::engine {

struct MeshVertex {
  float position[4];  // xyz, w = 1
  float normal[4];    // xyz unit; w: paint 0..1 (the demo's mesh shader blends in a hair-root colour), usually 0
};

struct Mesh {
  std::vector<MeshVertex> vertices;  // 3 per triangle, counter-clockwise seen from outside
  void append(const Mesh& other) { vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end()); }
};

struct MeshBounds {
  std::array<double, 3> min{};
  std::array<double, 3> max{};
};
MeshBounds mesh_bounds(const Mesh& mesh);

// A tapered capsule: the sphere of radius r0 at p0 swept to radius r1 at p1 (the shape of a TvkCapsule), so a
// collider and the mesh it stands for are the same surface. p0 == p1 gives a sphere.
Mesh make_capsule_mesh(const std::array<float, 3>& p0, float r0, const std::array<float, 3>& p1, float r1,
                       uint32_t segments = 32, uint32_t rings = 16);
// A horizontal square (normal +y) of half size `half_extent` centred at `center`.
Mesh make_floor_mesh(const std::array<float, 3>& center, float half_extent);

// Loads the triangles of an OBJ file (polygons are triangulated; normals are taken from the file or made from
// the faces). Throws engine::Error naming the file (and tinyobjloader's message) when it cannot be read or has
// no triangles.
Mesh load_obj_mesh(const std::filesystem::path& path);

}  // namespace tressvk::engine
