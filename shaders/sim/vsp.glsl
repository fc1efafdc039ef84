// The VSP pass's per-vertex math (see vsp.comp), shared by the pass-per-dispatch shader and the fused frame kernel.
#ifndef TRESSVK_SIM_VSP_GLSL
#define TRESSVK_SIM_VSP_GLSL
#include "sim/common.glsl"

// What VSP reads of the vertex's guide and substep, the same for every vertex of the strand (read after the pinned
// root vertices are integrated): the fused frame kernel reads it once per substep, the pass shader once per vertex.
struct VspStrand {
  bool on;          // a pinned root and a coefficient above zero
  float c;          // the coefficient, ramped toward 1 by the root's acceleration
  float keep;       // the group's velocity_keep
  vec3 p0, q0, r0;  // the root vertex now, a step and two steps back
  vec4 swing;       // the root's skinning rotation of this step
  vec4 swing_before;  // and of the step before (skin_delta_before)
};
// From the root vertices' state (vertex 0 and vertex 1: x now, y a step back, z two steps back), however the caller
// holds them.
VspStrand vsp_strand_from(uint g, vec4 x0, vec4 x1, vec3 y0, vec3 y1, vec3 z0, vec3 z1) {
  VspStrand s;
  GroupParams gp = guide_params(g);
  // VSP off for this group (the pass runs for another group). Any pin count: the root's rigid motion needs a pinned
  // root, and the acceleration is measured at the last pinned root vertex (vertex 1 when two or more are pinned).
  // Only pinned vertices are read, which nothing writes. (Chosen by value, not by index, so that the fused kernel's
  // private arrays are indexed by constants.)
  s.on = gp.vsp_coefficient > 0.0 && !(x0.w > 0.0);
  bool one_pinned = x1.w > 0.0;
  vec3 p0 = x0.xyz, p1 = one_pinned ? p0 : x1.xyz;
  vec3 q0 = y0, q1 = one_pinned ? q0 : y1;
  vec3 r0 = z0, r1 = one_pinned ? r0 : z1;

  // Above the acceleration threshold the whole strand follows the root rigidly; the coefficient ramps up over
  // [0.75, 1] x threshold so that it is a continuous function of the state.
  float accel = length((p1 - q1) - (q1 - r1));
  float ramp = clamp((accel - 0.75 * gp.vsp_threshold) / (0.25 * gp.vsp_threshold), 0.0, 1.0);
  s.c = mix(gp.vsp_coefficient, 1.0, ramp);
  s.keep = gp.velocity_keep;
  s.p0 = p0;
  s.q0 = q0;
  s.r0 = r0;
  // The rotation is the root's skinning rotation of this step (swing and twist, from double-precision poses);
  // the translation follows from the root vertex's move. Deriving the rotation from the root edge instead would
  // amplify float rounding of the pinned vertices by strand length / root edge length.
  s.swing = skin_delta(g);
  s.swing_before = skin_delta_before(g);
  return s;
}
VspStrand vsp_strand(uint g) {
  uint b = strand_base(g);
  return vsp_strand_from(g, TVK_POS(b), TVK_POS(b + TVK_BLOCK), TVK_PREV(b).xyz, TVK_PREV(b + TVK_BLOCK).xyz,
                         TVK_PREVPREV(b).xyz, TVK_PREVPREV(b + TVK_BLOCK).xyz);
}

void vsp_vertex_of(VspStrand s, uint i, uint v) {
  if (v < 1u || !s.on) return;
  vec4 x = TVK_POS(i);
  if (!(x.w > 0.0)) return;
  // The rigid motion of this step at the vertex's start-of-step position y, less the previous step's rigid motion
  // (at its position z then) that integrate already carried, damped, as velocity: with c = 1 a strand moving with
  // the head keeps moving with it, and c < 1 leaves the strand (1 - c) of the head's acceleration only. Nothing
  // is added to the history, so a change of c between steps (the ramp) gives no kick. rigid(x) - x is written
  // (p0 - q0) + (swing * (x - q0) - (x - q0)), without large cancellations; the previous step's rotation comes
  // from the host too (skin_delta_before).
  vec3 y = TVK_PREV(i).xyz;
  vec3 z = TVK_PREVPREV(i).xyz;
  precise vec3 now = (s.p0 - s.q0) + quat_rotate_delta(s.swing, y - s.q0);  // precise: see integrate.glsl
  precise vec3 before = (s.q0 - s.r0) + quat_rotate_delta(s.swing_before, z - s.r0);
  TVK_POS(i) = vec4(x.xyz + s.c * (now - s.keep * before), x.w);
}

void vsp_vertex(uint i, uint g, uint v) {
  if (v < 1u || !(TVK_POS(i).w > 0.0)) return;
  vsp_vertex_of(vsp_strand(g), i, v);
}

#endif
