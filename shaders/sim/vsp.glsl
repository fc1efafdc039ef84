// The VSP pass's per-vertex math (see vsp.comp), shared by the pass-per-dispatch shader and the fused frame kernel.
#ifndef TRESSVK_SIM_VSP_GLSL
#define TRESSVK_SIM_VSP_GLSL
#include "sim/common.glsl"

void vsp_vertex(uint i, uint g, uint v) {
  if (v < 1u) return;
  vec4 x = TVK_POS(i);
  if (!(x.w > 0.0)) return;

  GroupParams gp = guide_params(g);
  if (!(gp.vsp_coefficient > 0.0)) return;  // VSP off for this group (the pass runs for another group)
  uint b = strand_base(g);
  // Any pin count: the root's rigid motion needs a pinned root, and the acceleration is measured at the last pinned
  // root vertex (vertex 1 when two or more are pinned). Only pinned vertices are read, which nothing writes.
  if (TVK_POS(b).w > 0.0) return;
  uint b1 = TVK_POS(b + TVK_BLOCK).w > 0.0 ? b : b + TVK_BLOCK;
  vec3 p0 = TVK_POS(b).xyz, p1 = TVK_POS(b1).xyz;
  vec3 q0 = TVK_PREV(b).xyz, q1 = TVK_PREV(b1).xyz;
  vec3 r0 = TVK_PREVPREV(b).xyz, r1 = TVK_PREVPREV(b1).xyz;

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
  vec3 y = TVK_PREV(i).xyz;
  vec3 z = TVK_PREVPREV(i).xyz;
  vec3 now = (p0 - q0) + quat_rotate_delta(swing, y - q0);
  vec3 before = (q0 - r0) + quat_rotate_delta(skin_delta_before(g), z - r0);
  TVK_POS(i) = vec4(x.xyz + c * (now - gp.velocity_keep * before), x.w);
}

#endif
