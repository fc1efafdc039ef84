// The follow-the-leader model's passes (the default; the reference's SimModel::kFollowTheLeader) in the lane-parallel
// frame kernel (frame_lanes.glsl). Collision runs on every lane at once; the model's walks are serial along the strand
// (each vertex's step reads what the step before it made), so they run one vertex per exchange, the walk's state
// handed from lane to lane, with the arithmetic and the order of the one-thread-per-strand kernel's walks
// (local_shape.glsl, length.glsl: local_shape_step, wind_step, sweep_step). What a step reads of vertices it does not
// move is fetched from their lanes when it is final for the step, so both kernels give the same float results. A step
// costs one exchange and the step's arithmetic on the serial chain; everything else overlaps across lanes.
// Strands pinned at their tip too take the one-thread kernel (its tridiagonal Thomas solve is serial): the host
// chooses.
#ifndef TRESSVK_SIM_LANES_FTL_GLSL
#define TRESSVK_SIM_LANES_FTL_GLSL

struct LaneRest {
  float len;       // rest length of the edge leaving the vertex (segment v; 0 for the tip and padding lanes)
  float len_left;  // of the edge arriving (0 for the root)
  bool turns;      // local shape turns its frame onto the edge arriving at this vertex (rest_info z)
  vec3 edge;       // the edge leaving the vertex at rest, in the frame local shape carries (rest_edge_local)
};

LaneRest lane_rest(uint b, uint v) {
  LaneRest r = LaneRest(0.0, 0.0, false, vec3(0.0));
  if (v < N) {
    vec4 info = rest_info[b + v * TVK_BLOCK];
    if (v + 1u < N) r.len = info.x;
    r.turns = info.z != 0.0;
    r.edge = rest_edge_local[b + v * TVK_BLOCK].xyz;
  }
  if (v >= 1u && v < N) r.len_left = rest_info[b + (v - 1u) * TVK_BLOCK].x;
  return r;
}

// Local shape's step at vertex v (local_shape_step): f the frame carried from the root, a vertex v - 1 final, p
// vertex v as step v - 1 left it, n vertex v + 1 as the previous iteration left it. Leaves p final, and f and n moved
// for step v + 1.
void local_shape_lane_step(LaneRest lr, float s, inout vec4 f, vec3 a, inout vec4 p, inout vec4 n) {
  if (lr.turns) f = frame_align(f, p.xyz - a, lr.len_left);
  precise vec3 target = p.xyz + quat_rotate(f, lr.edge);  // precise: see integrate.glsl
  precise vec3 d = s * (target - n.xyz);
  if (p.w > 0.0) p = vec4(p.xyz - d, p.w);
  if (n.w > 0.0) n = vec4(n.xyz + d, n.w);
}

// Local shape (local_shape_strand): iterations in pairs, the second walk two vertices behind the first, as there. At
// exchange t lane t takes the first walk's step and lane t - 2 the second's; each reads from its left neighbour the
// frame and itself as moved (that neighbour's last step) and that neighbour final, and from its right neighbour the
// vertex as the iteration before left it (its lane steps after this one). Lane 1 starts a walk from the root frame
// and its own position; the tip's lane keeps what the step before it moved.
void local_shape_lanes(uint g, uint v, LaneRest lr, GroupParams gp) {
  float s = gp.local_stiffness;
  vec4 root = quat_mul(skin_rotation(g), root_frame[g]);
  bool vert = v >= 1u && v < N;
  vec4 carry_f = vec4(0, 0, 0, 1);
  vec4 carry_n = vec4(0.0);
  for (uint it = 0u; it < gp.local_iterations; it += 2u) {
    bool pair = it + 2u <= gp.local_iterations;
    uint last = pair ? N + 1u : N - 1u;
    for (uint t = 1u; t <= last; ++t) {
      lanes_put(v, carry_f, carry_n, L_pos);
      vec4 lf = lanes_get0(lane_before(v));
      vec4 ln = lanes_get1(lane_before(v));
      vec3 la = lanes_get2(lane_before(v)).xyz;
      vec4 rn = lanes_get2(lane_after(v));
      if (vert && (v == t || (pair && v + 2u == t))) {
        vec4 p = v == 1u ? L_pos : ln;
        if (v + 1u < N) {
          vec4 f = v == 1u ? root : lf;
          local_shape_lane_step(lr, s, f, la, p, rn);
          carry_f = f;
          carry_n = rn;
        }
        L_pos = p;
      }
    }
  }
}

void length_lanes(uint g, uint b, uint v, LaneRest lr, GroupParams gp, bool write_tangents) {
  bool vert = v < N;

  if (TVK_HAS(TVK_FEATURE_WIND)) {
    // wind_begin / wind_step: at exchange t lane t is pushed, against its left neighbour as pushed.
    float a = float(g % 20u) / 20.0;
    vec3 w = a * (step_params[TVK_STEP].wind[0].xyz + step_params[TVK_STEP].wind[2].xyz) +
             (1.0 - a) * (step_params[TVK_STEP].wind[1].xyz + step_params[TVK_STEP].wind[3].xyz);
    for (uint t = 1u; t < N; ++t) {
      lanes_put(v, L_pos, vec4(0.0), vec4(0.0));
      vec3 before = lanes_get0(lane_before(v)).xyz;
      if (v == t && L_pos.w > 0.0) {
        vec3 e = L_pos.xyz - before;
        float len = length(e);
        vec3 push = w;
        if (len > kDirectionEps * lr.len_left) {
          vec3 u = e / len;
          push = w - dot(w, u) * u;
        }
        L_pos = vec4(L_pos.xyz + push, L_pos.w);
      }
    }
  }

  // Every lane holds the anchor here (main), as collide_vertex reads it.
  if (TVK_HAS(TVK_FEATURE_COLLISION) && vert) collide_vertex(g, b, v);

  // The sweeps (length_strand's): at exchange t lane t steps segment t with itself as segment t - 1 moved it (its
  // left neighbour's carry) and its right neighbour as the passes before left it (fetched once per sweep); the last
  // sweep follows the leader and gives the parent its DFTL velocity (sweep_step writes this lane's history).
  for (uint it = 0u; it < gp.length_iterations; ++it) {
    lanes_put(v, L_pos, L_prev, vec4(0.0));
    vec4 n = lanes_get0(lane_after(v));
    vec3 pn = lanes_get1(lane_after(v)).xyz;
    SweepWalk sw = SweepWalk(L_pos, L_prev.xyz, it + 1u == gp.length_iterations);
    for (uint t = 0u; t < N; ++t) {
      if (t > 0u) {
        lanes_put(v, sw.p, vec4(0.0), vec4(0.0));
        vec4 moved = lanes_get0(lane_before(v));
        if (v == t) sw.p = moved;
      }
      if (v == t) L_pos = v + 1u < N ? sweep_step(sw, b, v, n, pn, lr.len) : sw.p;
    }
  }

  finish_lanes(g, b, v, gp, write_tangents);
}

#endif
