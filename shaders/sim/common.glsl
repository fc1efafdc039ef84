// Math shared by the simulation passes. Each function has a double-precision twin in
// plugin/model/include/tressvk/model/math.hpp (constants in model.hpp) written in the same order of
// operations, so the GPU and the reference differ only by float32 rounding.
#ifndef TRESSVK_SIM_COMMON_GLSL
#define TRESSVK_SIM_COMMON_GLSL

#include "sim/layout.glsl"

// State access. The pass-per-dispatch shaders read and write the state buffers; the fused frame kernel
// (frame.glsl) defines these first and maps them onto its on-chip copy of the strand, so that both paths run the
// same pass functions (integrate.glsl, vsp.glsl, local_shape.glsl, length.glsl, follow.glsl). i is always the
// element index of the blocked layout (vertex_index), g the guide.
#ifndef TVK_POS
#define TVK_POS(i) pos[i]
#define TVK_PREV(i) prev[i]
#define TVK_PREVPREV(i) prevprev[i]
#define TVK_ANCHOR(g) anchor[g]
#define TVK_STEP pc.step_index      // index into step_params of the substep being run
#define TVK_SKIN_BASE pc.skin_base  // first vec4 of that substep's skinning data
#endif

// Relative thresholds (all lengths are compared with a rest length, never with a constant in metres).
const float kDirectionEps = 1e-4;  // an edge shorter than this fraction of its rest length has no direction
const float kCollapse = 1.0;      // an edge shorter than this fraction of its rest length gets a blended direction
const float kContactBand = 0.02;  // capsule contacts this deep (fraction of the radius) lose all inward velocity
const float kFtlVelocityCorrection = 0.9;  // DFTL: share of a child's follow-the-leader move its parent gets back
const float kSolvePivotMin = 1e-6;  // the tip-pinned length solve's smallest pivot, relative to its row's diagonal

vec4 quat_mul(vec4 a, vec4 b) {
  return vec4(a.w * b.xyz + b.w * a.xyz + cross(a.xyz, b.xyz), a.w * b.w - dot(a.xyz, b.xyz));
}

vec3 quat_rotate(vec4 q, vec3 v) {
  vec3 t = 2.0 * cross(q.xyz, v);
  return v + q.w * t + cross(q.xyz, t);
}

// quat_rotate(q, v) - v, computed without cancellation for small rotations.
vec3 quat_rotate_delta(vec4 q, vec3 v) {
  vec3 t = 2.0 * cross(q.xyz, v);
  return q.w * t + cross(q.xyz, t);
}

// The minimal rotation taking unit vector a onto unit vector b. For (nearly) opposite vectors any half turn
// about an axis perpendicular to a is minimal; pick the one about the axis least aligned with a.
vec4 quat_from_two_unit(vec3 a, vec3 b) {
  float d = dot(a, b);
  if (d < -0.999999) {
    vec3 axis = abs(a.x) < 0.577 ? vec3(1, 0, 0) : (abs(a.y) < 0.577 ? vec3(0, 1, 0) : vec3(0, 0, 1));
    return vec4(normalize(cross(a, axis)), 0.0);
  }
  return normalize(vec4(cross(a, b), 1.0 + d));
}

// Fold guard: the amount of unit vector u to add to vector e (length el) so that e never points against u. Zero
// while e is within 90 degrees of u; beyond, 2 el cos^2 (C1 at 90 degrees), so a reversed e (cos = -1) becomes
// el * u. Without it a folded segment (one turned back on the frame's axis or on its own previous direction) gives
// a minimal rotation near a half turn, whose axis is undefined, or a blended direction near zero: float rounding
// then chooses the frame. With it the turn taken over one edge is at most about 97 degrees and a continuous,
// Lipschitz function of the edge, and it shrinks to nothing as the edge reverses.
float fold_guard(vec3 e, float el, vec3 u) {
  float eu = dot(e, u);
  return (eu < 0.0 && el > 0.0) ? 2.0 * (eu * eu / el) : 0.0;
}

// Turns frame q minimally so that its local +X points along edge e (rest length rest_len). An edge shorter than
// kCollapse x its rest length is blended with the frame's current +X by the missing length, so that its direction
// stays defined as it vanishes (a bare normalize(e) turns float rounding into arbitrary directions); at or above
// that length, and within 90 degrees of +X, it is e's own direction; beyond 90 degrees the fold guard applies.
vec4 frame_align(vec4 q, vec3 e, float rest_len) {
  vec3 x = quat_rotate(q, vec3(1, 0, 0));
  float el = length(e);
  vec3 d = e + (max(kCollapse * rest_len - el, 0.0) + fold_guard(e, el, x)) * x;
  float len = length(d);
  if (!(len > kDirectionEps * rest_len)) return q;
  // quat_from_two_unit(x, d / len), unnormalised (the product is normalised): (x cross d, |d| + x.d) is that
  // rotation times a positive factor. The fold guard keeps d within about 97 degrees of x, so the half-turn case
  // never arises here.
  return normalize(quat_mul(vec4(cross(x, d), len + dot(x, d)), q));
}

float strand_rest_length(uint g) { return uintBitsToFloat(guide_info[g].z); }

GroupParams guide_params(uint g) { return group[pc.group_base + guide_info[g].x]; }

// A strand its group carries rigidly (shorter than the group's rigid_below): every vertex takes inverse mass 0. The
// asset's own pins (rest_pos[].w) hold otherwise. Twin: the reference's effective inverse masses (Simulator).
bool strand_rigid(uint g, GroupParams gp) { return strand_rest_length(g) < gp.rigid_below; }

// The strand's blend of the affine rows at vec4 `slot` of each bone's skinning data (slot 0: asset space ->
// simulation space; slot 6: that map's change since the previous step). The same for every vertex of a strand in a
// substep: the fused frame kernel blends them once per substep.
struct SkinRows {
  vec4 r0, r1, r2;
};
SkinRows skin_rows(uint g, uint slot) {
  if (TVK_HAS(TVK_FEATURE_SKINNING)) {
    uvec4 bi = bone_index[g];
    vec4 bw = bone_weight[g];
    SkinRows m = SkinRows(vec4(0), vec4(0), vec4(0));
    for (uint i = 0u; i < 4u; ++i) {
      if (bw[i] == 0.0) continue;
      uint o = TVK_SKIN_BASE + TVK_SKIN_VEC4 * bi[i] + slot;
      m.r0 += bw[i] * skin[o];
      m.r1 += bw[i] * skin[o + 1u];
      m.r2 += bw[i] * skin[o + 2u];
    }
    return m;
  }
  uint o = TVK_SKIN_BASE + slot;
  return SkinRows(skin[o], skin[o + 1u], skin[o + 2u]);
}
// The rows applied to x (w = 1: a point, w = 0: a vector).
vec3 skin_rows_apply(SkinRows m, vec3 x, float w) {
  return vec3(dot(m.r0.xyz, x) + w * m.r0.w, dot(m.r1.xyz, x) + w * m.r1.w, dot(m.r2.xyz, x) + w * m.r2.w);
}
vec3 skin_apply(uint g, uint slot, vec3 x, float w) { return skin_rows_apply(skin_rows(g, slot), x, w); }

// The guide's anchor at the current substep: its skinned rest root, in simulation space.
vec3 skin_anchor(uint g) { return skin_apply(g, 0u, rest_pos[strand_base(g)].xyz, 1.0); }

// How far the guide's anchor moved since the previous substep (in this substep's frame).
vec3 anchor_move(uint g) { return skin_apply(g, 6u, rest_pos[strand_base(g)].xyz, 1.0); }

// Skinned rest position of guide vertex v, relative to the guide's anchor (the root: exactly zero).
vec3 skin_offset(uint g, uint v) {
  return v == 0u ? vec3(0.0) : skin_apply(g, 0u, rest_pos[vertex_index(g, v)].xyz, 0.0);
}

// Rotation of the strand's skinning (weights blended on the quaternion hemisphere of the first bone).
vec4 skin_rotation(uint g) {
  if (TVK_HAS(TVK_FEATURE_SKINNING)) {
    uvec4 bi = bone_index[g];
    vec4 bw = bone_weight[g];
    vec4 q0 = skin[TVK_SKIN_BASE + TVK_SKIN_VEC4 * bi[0] + 3u];
    vec4 q = vec4(0);
    for (uint i = 0u; i < 4u; ++i) {
      if (bw[i] == 0.0) continue;
      vec4 qi = skin[TVK_SKIN_BASE + TVK_SKIN_VEC4 * bi[i] + 3u];
      q += (dot(qi, q0) < 0.0 ? -bw[i] : bw[i]) * qi;
    }
    return normalize(q);
  }
  return skin[TVK_SKIN_BASE + 3u];
}

// Blends a per-bone rotation held at vec4 `slot` of each bone's skinning data with the strand's bone weights. The
// bone deltas it is used for are near identity with w >= 0, so no hemisphere flip is needed.
vec4 blend_bone_delta(uint g, uint slot) {
  if (TVK_HAS(TVK_FEATURE_SKINNING)) {
    uvec4 bi = bone_index[g];
    vec4 bw = bone_weight[g];
    vec4 q = vec4(0);
    for (uint i = 0u; i < 4u; ++i) {
      if (bw[i] == 0.0) continue;
      q += bw[i] * skin[TVK_SKIN_BASE + TVK_SKIN_VEC4 * bi[i] + slot];
    }
    return normalize(q);
  }
  return skin[TVK_SKIN_BASE + slot];
}

// The strand's skinning rotation since the previous step.
vec4 skin_delta(uint g) { return blend_bone_delta(g, 4u); }

// The same blend of the previous step's rotation since the one before (what integration carried as velocity).
vec4 skin_delta_before(uint g) { return blend_bone_delta(g, 5u); }

// The guide's root frame now: the skinned rest root frame, turned onto the current root edge when that edge is
// long enough (the same frame local shape starts from and follow hairs are turned by).
vec4 current_root_frame(uint g) {
  vec4 f = quat_mul(skin_rotation(g), root_frame[g]);
  uint b = strand_base(g);
  if (rest_info[b + TVK_BLOCK].z != 0.0) {
    f = frame_align(f, TVK_POS(b + TVK_BLOCK).xyz - TVK_POS(b).xyz, rest_info[b].x);
  }
  return f;
}

#endif
