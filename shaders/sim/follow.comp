// Pass 5, one thread per follow vertex: follow f of guide g is the guide plus its root offset turned by the
// guide's current root frame, spread toward the tip by the tip separation; it takes the guide's tangent.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sim/follow.glsl"
layout(local_size_x_id = 0) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint G = pc.guide_count;
  uvec2 sv = element_strand_vertex(i);  // threads walk the follow strands 0 .. G*K-1 in the blocked order
  uint strand = sv.x;
  uint v = sv.y;
  if (strand >= G * K || G + strand >= pc.follow_strands) return;
  uint f = strand / G;
  uint g = strand - f * G;
  GroupParams gp = guide_params(g);
  uint src = vertex_index(g, v);
  uint dst = vertex_index(G + strand, v);
  pos[dst] = follow_vertex(pos[src], follow_root_offset(g, f), gp.tip_separation, v);
}
