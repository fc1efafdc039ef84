// Pass 1, one thread per guide vertex: move the state with the simulation origin (and a teleport), rotate the
// history, Verlet-integrate with exponential damping and gravity, pin immovable vertices to the skinned rest
// pose, and pull toward the skinned rest pose over the global range (global shape constraints).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sim/common.glsl"
layout(local_size_x_id = 0) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.guide_count * N) return;
  uint g = i / N;
  uint v = i - g * N;

  vec4 rest = rest_pos[i];
  vec3 goal = skin_point(g, rest.xyz);
  uint flags = step_params[pc.step_index].flags.x;

  if ((flags & TVK_STEP_RESET) != 0u) {
    vec4 p = vec4(goal, rest.w);
    pos[i] = p;
    prev[i] = p;
    prevprev[i] = p;
    return;
  }

  vec3 p = pos[i].xyz;
  vec3 q = prev[i].xyz;
  vec3 r = prevprev[i].xyz;
  if ((flags & TVK_STEP_MOVE_STATE) != 0u) {
    // The origin moved (instance translation) and/or the instance teleported (a rotation about the new
    // origin): both are rigid, applied to the whole history, so they add no velocity.
    vec3 shift = step_params[pc.step_index].origin_shift.xyz;
    vec4 turn = step_params[pc.step_index].teleport;
    // The shift alone is exact (a multiple of 1/1024 m). With a turn, only p is carried as a point and the history
    // follows as turned differences, so the turn's rounding is common to all three and adds no velocity.
    if (all(equal(turn.xyz, vec3(0.0)))) {
      p -= shift;
      q -= shift;
      r -= shift;
    } else {
      vec3 pq = quat_rotate(turn, p - q);
      vec3 qr = quat_rotate(turn, q - r);
      p = quat_rotate(turn, p - shift);
      q = p - pq;
      r = q - qr;
    }
  }

  vec3 next;
  if (rest.w > 0.0) {
    GroupParams gp = guide_params(g);
    next = p + gp.velocity_keep * (p - q) + step_params[pc.step_index].gravity.xyz;
    if (TVK_HAS(TVK_FEATURE_GLOBAL_SHAPE)) {
      if (rest_info[i].y <= gp.global_range) next += gp.global_stiffness * (goal - next);
    }
  } else {
    next = goal;
  }
  prevprev[i] = vec4(q, rest.w);
  prev[i] = vec4(p, rest.w);
  pos[i] = vec4(next, rest.w);
}
