// Pass 1, one thread per guide vertex: write the guide's anchor (its skinned rest root), re-express the state
// against it (turned first by a teleport), Verlet-integrate with exponential damping and gravity, pin immovable
// vertices to the skinned rest pose, and pull toward the skinned rest pose over the global range (global shape
// constraints). Everything here is relative to the guide's anchor.
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

  float inv_mass = rest_pos[i].w;
  vec3 goal = skin_offset(g, v);
  uint flags = step_params[pc.step_index].flags.x;
  // Only this dispatch writes anchors and no pass before the length pass reads them.
  if (v == 0u) anchor[g] = vec4(skin_anchor(g), 0.0);

  if ((flags & TVK_STEP_RESET) != 0u) {
    vec4 p = vec4(goal, inv_mass);
    pos[i] = p;
    prev[i] = p;
    prevprev[i] = p;
    return;
  }

  vec3 p = pos[i].xyz;
  vec3 q = prev[i].xyz;
  vec3 r = prevprev[i].xyz;
  if ((flags & TVK_STEP_MOVE_STATE) != 0u) {
    // A teleport turns the whole history rigidly about the old anchor (the origin's own shift is part of the anchor's
    // move). Only p is turned as a point; the history follows as turned differences, so the turn's rounding is common
    // to all three and adds no velocity.
    vec4 turn = step_params[pc.step_index].teleport;
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
    next = p + gp.velocity_keep * (p - q) + step_params[pc.step_index].gravity.xyz;
    if (TVK_HAS(TVK_FEATURE_GLOBAL_SHAPE)) {
      if (rest_info[i].y <= gp.global_range) next += gp.global_stiffness * (goal - next);
    }
  } else {
    next = goal;
  }
  prevprev[i] = vec4(q, inv_mass);
  prev[i] = vec4(p, inv_mass);
  pos[i] = vec4(next, inv_mass);
}
