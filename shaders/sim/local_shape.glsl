// The local shape pass's per-strand math (see local_shape.comp), shared by the pass-per-dispatch shader and the
// fused frame kernel.
#ifndef TRESSVK_SIM_LOCAL_SHAPE_GLSL
#define TRESSVK_SIM_LOCAL_SHAPE_GLSL
#include "sim/common.glsl"

// One iteration's walk along the strand (vertices 1 .. N-2) as a state machine: the frame carried from the root, the
// two vertices the walk just moved (v - 1 finished, v moved by step v - 1), and the rest data of the edges around v,
// fetched one vertex ahead so that memory latency overlaps the arithmetic instead of stalling the serial walk.
struct LocalShapeWalk {
  vec4 f;
  vec4 a, p;
  vec4 info_in, info;
  vec3 edge;
};
LocalShapeWalk local_shape_begin(uint b, vec4 root, vec4 a, vec4 p) {
  return LocalShapeWalk(root, a, p, rest_info[b], rest_info[b + TVK_BLOCK], rest_edge_local[b + TVK_BLOCK].xyz);
}
// Step v with n = vertex v + 1 as it is now: turns the frame onto the edge arriving at v, moves v and n toward the
// rest shape, returns v (final for this iteration: later steps do not touch it) and carries n as the next step's v.
vec4 local_shape_step(inout LocalShapeWalk w, uint b, uint v, float s, vec4 n) {
  vec4 info_next = rest_info[b + (v + 1u) * TVK_BLOCK];
  vec3 edge_next = rest_edge_local[b + (v + 1u) * TVK_BLOCK].xyz;
  vec4 p = w.p;
  if (w.info.z != 0.0) w.f = frame_align(w.f, p.xyz - w.a.xyz, w.info_in.x);
  precise vec3 target = p.xyz + quat_rotate(w.f, w.edge);  // precise: see integrate.glsl
  precise vec3 d = s * (target - n.xyz);
  if (p.w > 0.0) p = vec4(p.xyz - d, p.w);
  if (n.w > 0.0) n = vec4(n.xyz + d, n.w);
  w.a = p;
  w.p = n;
  w.info_in = w.info;
  w.info = info_next;
  w.edge = edge_next;
  return p;
}

void local_shape_strand(uint g) {
  GroupParams gp = guide_params(g);
  float s = gp.local_stiffness;
  uint b = strand_base(g);  // vertex v at b + v * TVK_BLOCK
  vec4 root = quat_mul(skin_rotation(g), root_frame[g]);

  // The pass-per-dispatch shader holds the strand in a private array for the whole pass: one read and one write of
  // global memory per vertex, instead of a store-then-load round trip through the GPU's memory hierarchy at every
  // step of the serial walk. The fused kernel's state is already on chip: it walks it in place.
#ifdef TVK_FRAME_KERNEL
#define P(v) TVK_POS(b + (v) * TVK_BLOCK)
#else
  vec4 P_[N];
#define P(v) P_[v]
  for (uint v = 0u; v < N; ++v) P(v) = TVK_POS(b + v * TVK_BLOCK);
#endif
  // Iterations run in pairs in one pass along the strand, the second two vertices behind the first: step v of an
  // iteration reads vertex v + 1 as the iteration before left it (its step v + 1 is the last to move it) and nothing
  // else the first one still moves, so every step sees exactly the numbers of the iterations run one after the other,
  // while the two walks' serial chains overlap. An odd count ends with one walk alone.
  uint it = 0u;
  for (; it + 2u <= gp.local_iterations; it += 2u) {
    LocalShapeWalk w1 = local_shape_begin(b, root, P(0u), P(1u));
    LocalShapeWalk w2;
    for (uint t = 1u; t <= N; ++t) {
      if (t + 1u < N) {
        P(t) = local_shape_step(w1, b, t, s, P(t + 1u));
        if (t + 2u == N) P(N - 1u) = w1.p;
      }
      if (t == 3u) w2 = local_shape_begin(b, root, P(0u), P(1u));
      if (t >= 3u) P(t - 2u) = local_shape_step(w2, b, t - 2u, s, P(t - 1u));
    }
    P(N - 1u) = w2.p;
  }
  if (it < gp.local_iterations) {
    LocalShapeWalk w = local_shape_begin(b, root, P(0u), P(1u));
    for (uint v = 1u; v + 1u < N; ++v) P(v) = local_shape_step(w, b, v, s, P(v + 1u));
    P(N - 1u) = w.p;
  }
#ifndef TVK_FRAME_KERNEL
  for (uint v = 1u; v < N; ++v) TVK_POS(b + v * TVK_BLOCK) = P(v);
#endif
#undef P
}

#endif
