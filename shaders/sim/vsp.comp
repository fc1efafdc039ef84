// Pass 2, one thread per guide vertex (movable, of a strand with a pinned root): velocity shock propagation. Each thread derives its
// strand's root rigid motion of this step itself (the skinning rotation since the previous step about the root
// vertex, plus the root vertex's translation), so no strand-level pass or buffer is needed; then moves the vertex
// by coefficient * (this step's rigid motion - the damped previous one that integration already carried).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sim/common.glsl"
layout(local_size_x_id = 0) in;

void main() {
  uint i = gl_GlobalInvocationID.x;  // element i of the per-vertex buffers
  uvec2 sv = element_strand_vertex(i);
  uint g = sv.x;
  uint v = sv.y;
  if (g >= pc.guide_count) return;
  if (v < 1u) return;
  vec4 x = pos[i];
  if (!(x.w > 0.0)) return;

  GroupParams gp = guide_params(g);
  if (!(gp.vsp_coefficient > 0.0)) return;  // VSP off for this group (the pass runs for another group)
  uint b = strand_base(g);
  // Any pin count: the root's rigid motion needs a pinned root, and the acceleration is measured at the last pinned
  // root vertex (vertex 1 when two or more are pinned). Only pinned vertices are read, which nothing writes.
  if (pos[b].w > 0.0) return;
  uint b1 = pos[b + TVK_BLOCK].w > 0.0 ? b : b + TVK_BLOCK;
  vec3 p0 = pos[b].xyz, p1 = pos[b1].xyz;
  vec3 q0 = prev[b].xyz, q1 = prev[b1].xyz;
  vec3 r0 = prevprev[b].xyz, r1 = prevprev[b1].xyz;

  // Above the acceleration threshold the whole strand follows the root rigidly; the coefficient ramps up over
  // [0.75, 1] x threshold so that it is a continuous function of the state.
  float accel = length((p1 - q1) - (q1 - r1));
  float ramp = clamp((accel - 0.75 * gp.vsp_threshold) / (0.25 * gp.vsp_threshold), 0.0, 1.0);
  float c = mix(gp.vsp_coefficient, 1.0, ramp);

  // The rotation is the root's skinning rotation of this step (swing and twist, from double-precision poses);
  // the translation follows from the root vertex's move. Deriving the rotation from the root edge instead would
  // amplify float rounding of the pinned vertices by strand length / root edge length.
  vec4 swing = skin_delta(g);
  // The rigid motion of this step at the vertex's start-of-step position y, less the previous step's rigid motion
  // (at its position z then) that integrate already carried, damped, as velocity: with c = 1 a strand moving with
  // the head keeps moving with it, and c < 1 leaves the strand (1 - c) of the head's acceleration only. Nothing
  // is added to the history, so a change of c between steps (the ramp) gives no kick. rigid(x) - x is written
  // (p0 - q0) + (swing * (x - q0) - (x - q0)), without large cancellations; the previous step's rotation comes
  // from the host too (skin_delta_before).
  vec3 y = prev[i].xyz;
  vec3 z = prevprev[i].xyz;
  vec3 now = (p0 - q0) + quat_rotate_delta(swing, y - q0);
  vec3 before = (q0 - r0) + quat_rotate_delta(skin_delta_before(g), z - r0);
  pos[i] = vec4(x.xyz + c * (now - gp.velocity_keep * before), x.w);
}
