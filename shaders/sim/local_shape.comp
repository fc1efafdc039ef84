// Pass 3, one thread per guide (strands are independent): local shape constraints. All configured iterations
// run inside this one dispatch, for every N. A frame is carried from the skinned root frame along the current
// strand by minimal rotations (over edges long enough to have a direction); the rest edge leaving v, expressed in
// that frame, gives the target of v+1, and both ends move toward it (TressFX 3.x/4.0 semantics).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sim/local_shape.glsl"
layout(local_size_x_id = 0) in;

void main() {
  uint g = gl_GlobalInvocationID.x;
  if (g >= pc.guide_count) return;
  local_shape_strand(g);
}
