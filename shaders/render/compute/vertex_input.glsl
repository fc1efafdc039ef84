// The drawn vertex of one invocation of the compute rasterizer's vertex passes (project.comp, vertex.comp), after
// render/compute/raster_layout.glsl.
struct DrawnVertex {
  vec3 position, tangent;
  float along, tint;
  Material material;
  uint slot;  // where its data goes: its index, or its reversed strand's (order-independence test)
};

#include "render/strand_hash.glsl"

DrawnVertex drawn_vertex(uint id) {
  const uint n = dc.counts.x;
  const uint drawn = pc.params.y;
  const uint strand = id / n;
  const uint v = id % n;
  // The blocked layout of the simulation (TVK_STRAND_BLOCK = 32).
  const uint index = (strand / 32u) * (32u * n) + v * 32u + strand % 32u;
  DrawnVertex d;
  d.position = anchors[strand % dc.counts.y].xyz + positions[index].xyz;
  const uint g = strand % dc.counts.y;  // a follow's tangent is its guide's (the simulation stores the guides')
  d.tangent = tangents[(g / 32u) * (32u * n) + v * 32u + g % 32u].xyz;
  d.along = float(v) / float(n - 1u);
  d.material = dc.materials[min(guide_info[strand % dc.counts.y].x, 15u)];
  d.tint = 1.0 + d.material.fiber.z * (2.0 * strand_hash(strand) - 1.0);
  // Reversed submission (order-independence test): the same strands written in the opposite order.
  d.slot = (pc.params.z & kFlagReverse) != 0u ? (drawn - 1u - strand) * n + v : id;
  return d;
}
