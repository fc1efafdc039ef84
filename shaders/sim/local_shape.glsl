// The local shape pass's per-strand math (see local_shape.comp), shared by the pass-per-dispatch shader and the
// fused frame kernel.
#ifndef TRESSVK_SIM_LOCAL_SHAPE_GLSL
#define TRESSVK_SIM_LOCAL_SHAPE_GLSL
#include "sim/common.glsl"

void local_shape_strand(uint g) {
  GroupParams gp = guide_params(g);
  float s = gp.local_stiffness;
  uint b = strand_base(g);  // vertex v at b + v * TVK_BLOCK
  vec4 root = quat_mul(skin_rotation(g), root_frame[g]);

  // The strand lives in a private array for the whole pass: one read and one write of global memory per vertex,
  // instead of a store-then-load round trip through the GPU's memory hierarchy at every step of the serial walk.
  // The arithmetic is exactly the same.
  vec4 P[N];
  for (uint v = 0u; v < N; ++v) P[v] = TVK_POS(b + v * TVK_BLOCK);
  for (uint it = 0u; it < gp.local_iterations; ++it) {
    vec4 f = root;
    // The rest data of the next vertex is fetched one vertex ahead, so its memory latency overlaps this vertex's
    // arithmetic instead of stalling the serial walk.
    vec4 info_in = rest_info[b];
    vec4 info = rest_info[b + TVK_BLOCK];
    vec3 edge = rest_edge_local[b + TVK_BLOCK].xyz;
    for (uint v = 1u; v + 1u < N; ++v) {
      vec4 info_next = rest_info[b + (v + 1u) * TVK_BLOCK];
      vec3 edge_next = rest_edge_local[b + (v + 1u) * TVK_BLOCK].xyz;
      vec4 a = P[v - 1u];
      vec4 p = P[v];
      if (info.z != 0.0) f = frame_align(f, p.xyz - a.xyz, info_in.x);
      vec4 n = P[v + 1u];
      vec3 target = p.xyz + quat_rotate(f, edge);
      vec3 d = s * (target - n.xyz);
      if (p.w > 0.0) P[v] = vec4(p.xyz - d, p.w);
      if (n.w > 0.0) P[v + 1u] = vec4(n.xyz + d, n.w);
      info_in = info;
      info = info_next;
      edge = edge_next;
    }
  }
  for (uint v = 1u; v < N; ++v) TVK_POS(b + v * TVK_BLOCK) = P[v];
}

#endif
