// The drawn vertex of one invocation of the compute rasterizer's vertex passes (project.comp, vertex.comp), after
// render/compute/raster_layout.glsl.
struct DrawnVertex {
  vec3 position, tangent;
  float along, tint;
  Material material;
  uint slot;  // where its data goes: its index, or its reversed strand's (order-independence test)
};

#include "render/strand_hash.glsl"
#include "render/strand_layout.glsl"

DrawnVertex drawn_vertex(uint id) {
  const uint n = dc.counts.x;
  const uint drawn = pc.params.y;
  const uint strand = id / n;
  const uint v = id % n;
  const uint g = strand % dc.counts.y;  // its guide
  DrawnVertex d;
  d.position = anchors[g].xyz + positions[strand_element(strand, v, n)].xyz;
  d.tangent = tangents[strand_element(g, v, n)].xyz;
  d.along = float(v) / float(n - 1u);
  d.material = dc.materials[min(guide_info[g].x, 15u)];
  d.tint = 1.0 + d.material.fiber.z * (2.0 * strand_hash(strand) - 1.0);
  // Reversed submission (order-independence test): the same strands written in the opposite order.
  d.slot = (pc.params.z & kFlagReverse) != 0u ? (drawn - 1u - strand) * n + v : id;
  return d;
}
