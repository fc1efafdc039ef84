// Pass 2, one thread per guide vertex (v >= 2, movable): velocity shock propagation. Each thread derives its
// strand's root rigid motion of this step itself (the skinning rotation since the previous step about the root
// vertex, plus the root vertex's translation), so no strand-level pass or buffer is needed; then moves the vertex
// and its previous position by coefficient * (rigid motion), which keeps the velocity relative to the root.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sim/common.glsl"
layout(local_size_x_id = 0) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.guide_count * N) return;
  uint g = i / N;
  uint v = i - g * N;
  if (v < 2u) return;
  vec4 x = pos[i];
  if (!(x.w > 0.0)) return;

  GroupParams gp = guide_params(g);
  if (!(gp.vsp_coefficient > 0.0)) return;  // VSP off for this group (the pass runs for another group)
  uint b = g * N;
  vec3 p0 = pos[b].xyz, p1 = pos[b + 1u].xyz;
  vec3 q0 = prev[b].xyz, q1 = prev[b + 1u].xyz;
  vec3 r1 = prevprev[b + 1u].xyz;

  // Above the acceleration threshold the whole strand follows the root rigidly; the coefficient ramps up over
  // [0.75, 1] x threshold so that it is a continuous function of the state.
  float accel = length((p1 - q1) - (q1 - r1));
  float ramp = clamp((accel - 0.75 * gp.vsp_threshold) / (0.25 * gp.vsp_threshold), 0.0, 1.0);
  float c = mix(gp.vsp_coefficient, 1.0, ramp);

  // The rotation is the root's skinning rotation of this step (swing and twist, from double-precision poses);
  // the translation follows from the root vertex's move. Deriving the rotation from the root edge instead would
  // amplify float rounding of the pinned vertices by strand length / root edge length.
  vec4 swing = skin_delta(g);
  // rigid(x) - x = (p0 - q0) + (swing * (x - q0) - (x - q0)), written without large cancellations.
  vec3 t = p0 - q0;
  vec3 y = prev[i].xyz;
  vec3 dx = t + quat_rotate_delta(swing, x.xyz - q0);
  vec3 dy = t + quat_rotate_delta(swing, y - q0);
  pos[i] = vec4(x.xyz + c * dx, x.w);
  prev[i] = vec4(y + c * dy, x.w);
}
