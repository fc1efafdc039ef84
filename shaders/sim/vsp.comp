// Pass 2, one thread per guide vertex (v >= 2, movable): velocity shock propagation. Each thread derives its
// strand's root-edge rigid motion of this step itself (swing quaternion from the previous to the current root
// edge, plus the root translation), so no strand-level pass or buffer is needed; then moves the vertex and its
// previous position by coefficient * (rigid motion), which keeps the velocity relative to the root.
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

  vec4 swing = vec4(0, 0, 0, 1);
  if ((guide_info[g].y & TVK_GUIDE_ROOT_SWING) != 0u) {
    vec3 u = q1 - q0;
    vec3 w = p1 - p0;
    float min_len = kDirectionEps * rest_info[b].x;
    float lu = length(u), lw = length(w);
    if (lu > min_len && lw > min_len) swing = quat_from_two_unit(u / lu, w / lw);
  }
  // rigid(x) - x = (p0 - q0) + (swing * (x - q0) - (x - q0)), written without large cancellations.
  vec3 t = p0 - q0;
  vec3 y = prev[i].xyz;
  vec3 dx = t + quat_rotate_delta(swing, x.xyz - q0);
  vec3 dy = t + quat_rotate_delta(swing, y - q0);
  pos[i] = vec4(x.xyz + c * dx, x.w);
  prev[i] = vec4(y + c * dy, x.w);
}
