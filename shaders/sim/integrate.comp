// Pass 1, one thread per guide vertex: write the guide's anchor (its skinned rest root), re-express the state
// against it (turned first by a teleport), Verlet-integrate with exponential damping and gravity, pin immovable
// vertices to the skinned rest pose, and pull toward the skinned rest pose over the global range (global shape
// constraints). Everything here is relative to the guide's anchor.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sim/integrate.glsl"
layout(local_size_x_id = 0) in;

void main() {
  uint i = gl_GlobalInvocationID.x;  // element i of the per-vertex buffers
  uvec2 sv = element_strand_vertex(i);
  if (sv.x >= pc.guide_count) return;
  integrate_vertex(i, sv.x, sv.y);
}
