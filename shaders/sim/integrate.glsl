// The integrate pass's per-vertex math (see integrate.comp), shared by the pass-per-dispatch shader and the fused
// frame kernel (frame.glsl). Element i of the per-vertex buffers is vertex v of guide g.
#ifndef TRESSVK_SIM_INTEGRATE_GLSL
#define TRESSVK_SIM_INTEGRATE_GLSL
#include "sim/common.glsl"

// What integration reads of the vertex's guide and substep, the same for every vertex of the strand: the fused frame
// kernel reads it once per substep, the pass shader once per vertex.
struct IntegrateStrand {
  uint flags;
  vec4 turn;       // the teleport's turn of the state (with TVK_STEP_MOVE_STATE)
  vec3 move;       // the anchor's move since the previous substep
  vec3 gravity;    // g h^2
  SkinRows rest;   // the skinning map (slot 0)
  GroupParams gp;
  bool rigid;      // carried rigidly (strand_rigid)
};
IntegrateStrand integrate_strand(uint g) {
  IntegrateStrand s;
  s.flags = step_params[TVK_STEP].flags.x;
  s.turn = step_params[TVK_STEP].teleport;
  s.move = anchor_move(g);
  s.gravity = step_params[TVK_STEP].gravity.xyz;
  s.rest = skin_rows(g, 0u);
  s.gp = guide_params(g);
  s.rigid = strand_rigid(g, s.gp);
  return s;
}

void integrate_vertex_of(IntegrateStrand s, uint i, uint g, uint v) {
  vec4 rest = rest_pos[i];
  float inv_mass = s.rigid ? 0.0 : rest.w;
  // skin_offset(g, v) and skin_anchor(g) with the strand's rows (i is vertex v of guide g).
  vec3 goal = v == 0u ? vec3(0.0) : skin_rows_apply(s.rest, rest.xyz, 0.0);
  uint flags = s.flags;
  // Only this dispatch writes anchors and no pass before the length pass reads them.
  if (v == 0u) TVK_ANCHOR(g) = vec4(skin_rows_apply(s.rest, rest.xyz, 1.0), 0.0);

  if ((flags & TVK_STEP_RESET) != 0u) {
    vec4 p = vec4(goal, inv_mass);
    TVK_POS(i) = p;
    TVK_PREV(i) = p;
    TVK_PREVPREV(i) = p;
    return;
  }

  vec3 p = TVK_POS(i).xyz;
  vec3 q = TVK_PREV(i).xyz;
  vec3 r = TVK_PREVPREV(i).xyz;
  if ((flags & TVK_STEP_MOVE_STATE) != 0u) {
    // A teleport turns the whole history rigidly about the old anchor (the origin's own shift is part of the anchor's
    // move). Only p is turned as a point; the history follows as turned differences, so the turn's rounding is common
    // to all three and adds no velocity.
    vec4 turn = s.turn;
    if (any(notEqual(turn.xyz, vec3(0.0)))) {
      vec3 pq = quat_rotate(turn, p - q);
      vec3 qr = quat_rotate(turn, q - r);
      p = quat_rotate(turn, p);
      q = p - pq;
      r = q - qr;
    }
  }
  // Re-expressed against this step's anchor: the same move for the whole history and the whole strand, so it is
  // rigid and adds no velocity (its rounding is relative to the move, not to the anchor's distance from the origin).
  vec3 move = s.move;
  p -= move;
  q -= move;
  r -= move;

  // precise: no fused multiply-add contraction (here, in local shape's step and in VSP). Which products a compiler
  // fuses decides how float32 rounding enters the strand, and tight curls (8.5 vertices per turn) amplify it about
  // 150-fold: on an NVIDIA H100 the contracted code gave a step error of 1.2e-5 of the strand length on the
  // tight-curl hard case (the bar is 1e-5), 6.6e-6 without contraction; the cost measured 0 to 2 % (Ratboy 240 Hz
  // 223 -> 214 us, curly 1M 593 -> 607 us). docs/accuracy.md, "Hard cases".
  precise vec3 next;
  if (inv_mass > 0.0) {
    next = p + s.gp.velocity_keep * (p - q) + s.gravity;
    if (TVK_HAS(TVK_FEATURE_GLOBAL_SHAPE)) {
      if (rest_info[i].y <= s.gp.global_range) next += s.gp.global_stiffness * (goal - next);
    }
  } else {
    next = goal;
  }
  TVK_PREVPREV(i) = vec4(q, inv_mass);
  TVK_PREV(i) = vec4(p, inv_mass);
  TVK_POS(i) = vec4(next, inv_mass);
}

void integrate_vertex(uint i, uint g, uint v) { integrate_vertex_of(integrate_strand(g), i, g, v); }

#endif
