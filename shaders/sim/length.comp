// Pass 4, one thread per guide: wind, capsule collision, length constraints (root-to-tip Gauss-Seidel sweeps,
// the last one follow-the-leader, so a collision push never leaves a stretched segment), velocity clamp, the
// non-finite check (a strand that went NaN/Inf is reset to its skinned rest pose and counted, so it never
// spreads), and tangents. Terms not compiled in (FEATURES, CAPSULE_COUNT) cost nothing.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sim/length.glsl"
layout(local_size_x_id = 0) in;

void main() {
  uint g = gl_GlobalInvocationID.x;
  if (g >= pc.guide_count) return;
  length_strand(g, true);
}
