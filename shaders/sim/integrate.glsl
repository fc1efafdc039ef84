// The integrate pass's per-vertex math (see integrate.comp), shared by the pass-per-dispatch shader and the fused
// frame kernel (frame.glsl). Element i of the per-vertex buffers is vertex v of guide g.
#ifndef TRESSVK_SIM_INTEGRATE_GLSL
#define TRESSVK_SIM_INTEGRATE_GLSL
#include "sim/common.glsl"

void integrate_vertex(uint i, uint g, uint v) {

  float inv_mass = rest_pos[i].w;
  vec3 goal = skin_offset(g, v);
  uint flags = step_params[TVK_STEP].flags.x;
  // Only this dispatch writes anchors and no pass before the length pass reads them.
  if (v == 0u) TVK_ANCHOR(g) = vec4(skin_anchor(g), 0.0);

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
    vec4 turn = step_params[TVK_STEP].teleport;
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
  vec3 move = anchor_move(g);
  p -= move;
  q -= move;
  r -= move;

  vec3 next;
  if (inv_mass > 0.0) {
    GroupParams gp = guide_params(g);
    next = p + gp.velocity_keep * (p - q) + step_params[TVK_STEP].gravity.xyz;
    if (TVK_HAS(TVK_FEATURE_GLOBAL_SHAPE)) {
      if (rest_info[i].y <= gp.global_range) next += gp.global_stiffness * (goal - next);
    }
  } else {
    next = goal;
  }
  TVK_PREVPREV(i) = vec4(q, inv_mass);
  TVK_PREV(i) = vec4(p, inv_mass);
  TVK_POS(i) = vec4(next, inv_mass);
}

#endif
