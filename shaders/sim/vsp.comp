// Pass 2, one thread per guide vertex (movable, of a strand with a pinned root): velocity shock propagation. Each
// thread derives its strand's root rigid motion of this step itself (the skinning rotation since the previous step about the root
// vertex, plus the root vertex's translation), so no strand-level pass or buffer is needed; then moves the vertex
// by coefficient * (this step's rigid motion - the damped previous one that integration already carried).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sim/vsp.glsl"
layout(local_size_x_id = 0) in;

void main() {
  uint i = gl_GlobalInvocationID.x;  // element i of the per-vertex buffers
  uvec2 sv = element_strand_vertex(i);
  if (sv.x >= pc.guide_count) return;
  vsp_vertex(i, sv.x, sv.y);
}
