// The follow pass's math (see follow.comp), shared by the pass-per-dispatch shader and the fused frame kernel:
// follow f of guide g is the guide plus its root offset turned by the guide's current root frame, spread toward
// the tip by the tip separation.
#ifndef TRESSVK_SIM_FOLLOW_GLSL
#define TRESSVK_SIM_FOLLOW_GLSL
#include "sim/common.glsl"

// The offset of follow f of guide g from its guide, in simulation space, before the spread.
vec3 follow_root_offset(uint g, uint f) { return quat_rotate(current_root_frame(g), follow_offset[g * K + f].xyz); }

// Vertex v of the follow, from the guide's vertex v.
vec4 follow_vertex(vec4 guide, vec3 offset, float tip_separation, uint v) {
  float spread = 1.0 + tip_separation * float(v) / float(N - 1u);
  return vec4(guide.xyz + spread * offset, guide.w);
}

#endif
