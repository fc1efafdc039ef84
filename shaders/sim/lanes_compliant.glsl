// The compliant model's passes in the lane-parallel frame kernel (frame_lanes.glsl; the reference's
// SimModel::kCompliant, docs/accuracy.md). Every per-substep solve is parallel over the lanes: the shape targets are
// local (one minimal rotation per edge), the local-shape and length systems are tridiagonal and solved by parallel
// cyclic reduction (log2 lanes steps), the damped Newton scale and the stretch test are reductions. The order is the
// reference's (plugin/reference/src/simulator.cpp, local_shape_compliant and the kCompliant branch of
// length_and_collision).
//
// The host uploads the compliant constants in GroupParams: global_stiffness = the global spring's fraction at this h,
// reserved0 = the bending compliance alpha / h^2 at the calibration edge (31 edges per strand), reserved1 = the
// bending damping tau / h at the calibration edge (an edge of relative length rel takes it times min(1 / rel^2, 4)).
#ifndef TRESSVK_SIM_LANES_COMPLIANT_GLSL
#define TRESSVK_SIM_LANES_COMPLIANT_GLSL

const float kCalibrationSegments = 31.0;
const float kBendDampingGrowthCap = 4.0;  // the reference's compliant_bend_damping_edge
const uint kCompliantExtraNewton = 4u;
const float kCompliantStretchTol = 1e-3;
const float kCompliantReachFloorRel = 0.5;
const float kConservativeFallbackStretch = 4e-3;  // the reference's (length_fallback_lanes)


// Solves the tridiagonal system whose row r lane r holds (sub a, diagonal b, super c, right-hand side d; rows that are
// not part of the system are the identity) by parallel cyclic reduction; returns x_r. Each step a lane publishes the
// reciprocal of its diagonal, so that it divides once. (Publishing the row divided by its diagonal instead exchanges
// two or four floats fewer a step: on an NVIDIA H100 3-9 % faster at 60 Hz, 0.6-5 % at 240 Hz, but Ratboy's step
// error at 60 Hz went from 1.2e-6 to 3.0e-6 of its length; not taken.) TVK_TRIDIAGONAL(name, T) makes the solver for a right-hand side
// of type T (float for the length rows, vec3 for the shape and transverse rows).
#define TVK_TRIDIAGONAL(name, T)                                                                                      \
  T name(uint r, float a, float b, float c, T d) {                                                                    \
    TVK_EXCHANGE_LOOP for (uint s = 1u; s < LANES; s <<= 1u) {                                                                \
      float ib = 1.0 / b;                                                                                             \
      lanes_put(r, vec4(a, ib, c, 0.0), to4(d), vec4(0.0));                                                           \
      uint lo = r >= s ? r - s : r;                                                                                   \
      uint hi = r + s < LANES ? r + s : r;                                                                            \
      vec4 L = lanes_get0(lo);                                                                                        \
      T Ld;                                                                                                           \
      unpack4(lanes_get1(lo), Ld);                                                                                    \
      vec4 H = lanes_get0(hi);                                                                                        \
      T Hd;                                                                                                           \
      unpack4(lanes_get1(hi), Hd);                                                                                    \
      float a2 = 0.0, b2 = b, c2 = 0.0;                                                                               \
      T d2 = d;                                                                                                       \
      if (r >= s) {                                                                                                   \
        float al = -a * L.y;                                                                                          \
        a2 = al * L.x;                                                                                                \
        b2 += al * L.z;                                                                                               \
        d2 += al * Ld;                                                                                                \
      }                                                                                                               \
      if (r + s < LANES) {                                                                                            \
        float ga = -c * H.y;                                                                                          \
        c2 = ga * H.z;                                                                                                \
        b2 += ga * H.x;                                                                                               \
        d2 += ga * Hd;                                                                                                \
      }                                                                                                               \
      a = a2;                                                                                                         \
      b = b2;                                                                                                         \
      c = c2;                                                                                                         \
      d = d2;                                                                                                         \
    }                                                                                                                 \
    return d / b;                                                                                                     \
  }
TVK_TRIDIAGONAL(lanes_tridiagonal3, vec3)
TVK_TRIDIAGONAL(lanes_tridiagonal1, float)

// The same with one step of iterative refinement: the residual of the first solution (in float, from the lanes'
// neighbours) solved again and added. Parallel cyclic reduction's float error grows with the system's condition
// (~N^2 for the weakly diagonally dominant length and shape systems) times the solution, which carries the strand's
// whole load at low step rates; one refinement brings it back to rounding. (Skipping it where every row's residual
// is already at rounding level measured slower on NVIDIA: the test costs a reduction per solve.) The shape and
// transverse solves use it; the length solve's Newton steps do not: each step is solved from the residual the step
// before left, so an unrefined step's float error is what the next one corrects (NVIDIA H100, 240 Hz: Ratboy 113.5 ->
// 107.8 us, curly 1 M 1,187 -> 1,107, 4 M 4,529 -> 4,130, step errors unchanged; refining only the last of the
// shape's iterations as well was faster again but put Ratboy's step error at 60 Hz at 3.5e-5, over the 1e-5 bar).
#define TVK_TRIDIAGONAL_REFINED(name, solve, T)                                                                       \
  T name(uint r, float a, float b, float c, T d) {                                                                    \
    T x = solve(r, a, b, c, d);                                                                                       \
    lanes_put(r, to4(x), vec4(0.0), vec4(0.0));                                                                      \
    T xl, xr;                                                                                                         \
    unpack4(lanes_get0(lane_before(r)), xl);                                                                          \
    unpack4(lanes_get0(lane_after(r)), xr);                                                                           \
    T res = d - b * x;                                                                                                \
    if (r > 0u) res -= a * xl;                                                                                        \
    if (r + 1u < LANES) res -= c * xr;                                                                                \
    return x + solve(r, a, b, c, res);                                                                                \
  }
TVK_TRIDIAGONAL_REFINED(lanes_tridiagonal_refined, lanes_tridiagonal3, vec3)

// ---- the lane's rest data, read once per frame ----------------------------------------------------------------------

struct LaneRest {
  float arc;       // rest arc length of the vertex from the root / strand rest length (the global shape's range)
  float len;       // rest length of the edge leaving the vertex (0 for the tip and padding lanes)
  float len_left;  // of the edge arriving (0 for the root)
  bool turns;      // the local-shape frame turns onto the edge leaving the vertex (rest_info z of the vertex after)
  vec3 edge;       // the edge leaving the vertex at rest, in the asset's frame
  int frame_edge;  // the last edge before this one whose frame turns (-1: none)
};

LaneRest lane_rest(uint b, uint v) {
  LaneRest r;
  r.len = 0.0;
  r.len_left = 0.0;
  r.turns = false;
  r.edge = vec3(0.0);
  r.frame_edge = -1;
  r.arc = v < N ? rest_info[b + v * TVK_BLOCK].y : 0.0;
  if (v + 1u < N) {
    r.len = rest_info[b + v * TVK_BLOCK].x;
    r.turns = rest_info[b + (v + 1u) * TVK_BLOCK].z != 0.0;
    vec3 from = v == 0u ? vec3(0.0) : rest_pos[b + v * TVK_BLOCK].xyz;
    r.edge = rest_pos[b + (v + 1u) * TVK_BLOCK].xyz - from;
  }
  if (v >= 1u && v < N) r.len_left = rest_info[b + (v - 1u) * TVK_BLOCK].x;
  if (v < N) {
    for (uint j = v; j-- > 0u;) {
      if (rest_info[b + (j + 1u) * TVK_BLOCK].z != 0.0) {
        r.frame_edge = int(j);
        break;
      }
    }
  }
  return r;
}

// ---- the compliant model's passes ------------------------------------------------------------------------------------

// Both local shapes' first step: every edge's direction u (constraint_direction), then each constraint's target: its
// skinned rest edge turned by the minimal rotation of the last edge before it that turns the frame, from that edge's
// skinned rest direction onto its current one. Each lane makes the rotation of its own edge; a lane takes the one of
// its frame edge, or of the frame edge before that while an edge is too short to have a direction (jf: the edge it
// took, -1: none). np, nq: the next vertex's position and history.
struct ShapeTarget {
  vec4 np;
  vec3 nq;
  vec3 u;
  vec3 target;
  int jf;
};
ShapeTarget lanes_shape_target(uint v, LaneRest lr, bool row, vec3 rest_dir) {
  ShapeTarget t;
  lanes_put(v, L_pos, L_prev, vec4(0.0));
  t.np = lanes_get0(lane_after(v));
  t.nq = lanes_get1(lane_after(v)).xyz;
  t.u = vec3(0.0);
  if (v + 1u < N) t.u = constraint_direction(t.np.xyz - L_pos.xyz, t.nq - L_prev.xyz, lr.len);
  bool turns_here = lr.turns && dot(t.u, t.u) > 0.0;
  vec4 turn = turns_here ? quat_from_two_unit(normalize(rest_dir), t.u) : vec4(0, 0, 0, 1);
  lanes_put(v, turn, vec4(turns_here ? 1.0 : 0.0, float(lr.frame_edge), 0.0, 0.0), vec4(0.0));
  vec4 q = vec4(0, 0, 0, 1);
  int j = row ? lr.frame_edge : -1;
  t.jf = -1;
  TVK_EXCHANGE_LOOP for (uint round = 0u; round < N; ++round) {
    uint src = j >= 0 ? uint(j) : v;
    vec4 qj = lanes_get0(src);
    vec4 info = lanes_get1(src);
    if (j >= 0) {
      if (info.x > 0.5) {
        q = qj;
        t.jf = j;
        j = -1;
      } else {
        j = int(info.y);
      }
    }
    if (!lanes_any(v, j >= 0)) break;
  }
  t.target = row ? quat_rotate(q, rest_dir) : vec3(0.0);
  return t;
}

const float kConservativeCalibration = 0.080;    // model::kConservativeCalibration
const float kConservativeDampingScale = 0.3;     // model::kConservativeDampingScale

// A symmetric 3x3 block inverted from its cofactors (one triangle). GLSL's inverse() of the normal equations' pivots
// sent about one strand in ten of Ratboy and the straight groom out of control on lavapipe and the H100 alike, from
// the first frame; the cofactors of either triangle did not (not understood; the blocks were checked symmetric).
mat3 inverse_sym(mat3 a) {
  float c00 = a[1][1] * a[2][2] - a[1][2] * a[1][2];
  float c01 = a[1][2] * a[0][2] - a[0][1] * a[2][2];
  float c02 = a[0][1] * a[1][2] - a[1][1] * a[0][2];
  float c11 = a[0][0] * a[2][2] - a[0][2] * a[0][2];
  float c12 = a[0][1] * a[0][2] - a[0][0] * a[1][2];
  float c22 = a[0][0] * a[1][1] - a[0][1] * a[0][1];
  float id = 1.0 / (a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02);
  return mat3(c00, c01, c02, c01, c11, c12, c02, c12, c22) * id;
}

// Node v of a strand's system in s_blk (kNodeFloats floats from kNodeFloats * node): what lane v writes (G_v's block on
// x_{v-1} at 0, its coefficient on x_{v+1} at 9, M_v = 1 / w_v at 10, the compliance at 11, G_v's block on x_v at
// 12, the right-hand side at 21), then what the solver writes over the last four once it has read them (D_v^-1 at 10:
// its xx and mm blocks as symmetric 3x3s, its mx block; z_v at 31, then the solution u_v = (dx_v, -dlambda_v)).
mat3 node_m3(uint o) {
  return mat3(s_blk[o], s_blk[o + 1u], s_blk[o + 2u], s_blk[o + 3u], s_blk[o + 4u], s_blk[o + 5u], s_blk[o + 6u],
              s_blk[o + 7u], s_blk[o + 8u]);
}
void node_set_m3(uint o, mat3 a) {
  for (uint c = 0u; c < 3u; ++c)
    for (uint i = 0u; i < 3u; ++i) s_blk[o + 3u * c + i] = a[c][i];
}
mat3 node_sym(uint o) {  // xx, yy, zz, xy, xz, yz
  return mat3(s_blk[o], s_blk[o + 3u], s_blk[o + 4u], s_blk[o + 3u], s_blk[o + 1u], s_blk[o + 5u], s_blk[o + 4u],
              s_blk[o + 5u], s_blk[o + 2u]);
}
void node_set_sym(uint o, mat3 a) {
  s_blk[o] = a[0][0];
  s_blk[o + 1u] = a[1][1];
  s_blk[o + 2u] = a[2][2];
  s_blk[o + 3u] = a[0][1];
  s_blk[o + 4u] = a[0][2];
  s_blk[o + 5u] = a[1][2];
}
vec3 node_v3(uint o) { return vec3(s_blk[o], s_blk[o + 1u], s_blk[o + 2u]); }
void node_set_v3(uint o, vec3 x) {
  s_blk[o] = x.x;
  s_blk[o + 1u] = x.y;
  s_blk[o + 2u] = x.z;
}

// A strand's system (conservative_shape_lanes) in s_blk: node v's unknowns are (dx_v, mu_v = -dlambda_v); its diagonal
// block is [[M_v I, Gs^T], [Gs, -a_v I]], the block to node v - 1 [[0, g_{v-1} I], [Gp_v, 0]]: block-tridiagonal in
// 6x6 blocks. It is factorised from both ends at once (a twisted block LDL^T): one invocation eliminates nodes 0 ..
// k - 1 downwards, another nodes n - 1 .. k + 1 upwards, both hand node k what they make of it through the strand's
// exchange floats, and after a barrier each solves node k and substitutes back towards its end. Every pivot is a
// Schur complement of a quasi-definite matrix, [[A, B^T], [B, -C]] with A and C positive definite, and is inverted
// through its own Schur complement S = -C - B A^-1 B^T in registers. The exchange (from base + n * kNodeFloats):
// 0..26 the lower half's part of node k (its xx, mm blocks as symmetric 3x3s, its mx block, its right-hand side),
// 27..32 the upper half's right-hand side of node k (its pivot's blocks go to node k's own floats 10..30).

// [[a, bb^T], [bb, -c]]^-1 as its xx, mm (symmetric) and mx blocks.
void pivot_inverse(mat3 a, mat3 bb, mat3 c, out mat3 pxx, out mat3 pmm, out mat3 pmx) {
  mat3 ai = inverse_sym(a);
  mat3 e = bb * ai;
  pmm = inverse_sym(-c - e * transpose(bb));
  pmx = -pmm * e;
  pxx = ai - transpose(e) * pmx;
}

// Nodes 0 .. k - 1 eliminated downwards (D_v = K(v, v) - K(v, v-1) D_{v-1}^-1 K(v, v-1)^T, z_v = rhs_v - K(v, v-1)
// D_{v-1}^-1 z_{v-1}; D_v^-1 written over node v's floats 10..30, z_v at 31), then node k's part of D_k and z_k.
void solve_upper_half(uint base, uint n, uint k) {
  mat3 pxx = mat3(0.0), pmm = mat3(0.0), pmx = mat3(0.0);  // D_{v-1}^-1
  vec3 zx = vec3(0.0), zm = vec3(0.0);                      // z_{v-1}
  float g = 0.0;                                            // g_{v-1}
  for (uint v = 0u; v <= k; ++v) {
    uint o = base + kNodeFloats * v;
    mat3 gp = node_m3(o), gs = node_m3(o + 12u);
    float m = s_blk[o + 10u], al = s_blk[o + 11u];
    vec3 b = node_v3(o + 21u);
    vec3 yx = pxx * zx + transpose(pmx) * zm, ym = pmx * zx + pmm * zm;
    zx = -g * ym;
    zm = b - gp * yx;
    mat3 a = m * mat3(1.0) - (g * g) * pmm;
    mat3 bb = gs - g * gp * transpose(pmx);
    mat3 c = al * mat3(1.0) + gp * pxx * transpose(gp);
    if (v == k) {
      node_set_sym(o + 10u, a);
      node_set_sym(o + 16u, c);
      node_set_m3(o + 22u, bb);
      uint e = base + kNodeFloats * n;
      node_set_v3(e + 27u, zx);
      node_set_v3(e + 30u, zm);
      break;
    }
    pivot_inverse(a, bb, c, pxx, pmm, pmx);
    node_set_sym(o + 10u, pxx);
    node_set_sym(o + 16u, pmm);
    node_set_m3(o + 22u, pmx);
    node_set_v3(o + 31u, zx);
    node_set_v3(o + 34u, zm);
    g = s_blk[o + 9u];
  }
}

// Nodes n - 1 .. k + 1 eliminated upwards (E_v = K(v, v) - K(v, v+1) E_{v+1}^-1 K(v, v+1)^T, w_v likewise; written
// as the upper half writes), then their part of node k: K(k, k+1) E_{k+1}^-1 K(k, k+1)^T and K(k, k+1) E_{k+1}^-1 w_{k+1}.
void solve_lower_half(uint base, uint n, uint k) {
  mat3 qxx = mat3(0.0), qmm = mat3(0.0), qmx = mat3(0.0);  // E_{v+1}^-1
  vec3 wx = vec3(0.0), wm = vec3(0.0);                      // w_{v+1}
  for (uint v = n; v-- > k;) {
    uint o = base + kNodeFloats * v;
    // (index clamped into the strand's nodes: a select may read both sides)
    mat3 gpn = v + 1u < n ? node_m3(base + kNodeFloats * min(v + 1u, n - 1u)) : mat3(0.0);  // Gp_{v+1}
    float g = s_blk[o + 9u];
    vec3 yx = qxx * wx + transpose(qmx) * wm, ym = qmx * wx + qmm * wm;
    mat3 a = transpose(gpn) * qmm * gpn;
    mat3 bb = g * transpose(qmx) * gpn;
    mat3 c = (g * g) * qxx;
    if (v == k) {
      uint e = base + kNodeFloats * n;
      node_set_sym(e, a);
      node_set_sym(e + 6u, c);
      node_set_m3(e + 12u, bb);
      node_set_v3(e + 21u, transpose(gpn) * ym);
      node_set_v3(e + 24u, g * yx);
      break;
    }
    wx = -transpose(gpn) * ym;
    wm = node_v3(o + 21u) - g * yx;
    pivot_inverse(s_blk[o + 10u] * mat3(1.0) - a, node_m3(o + 12u) - bb, s_blk[o + 11u] * mat3(1.0) + c, qxx, qmm,
                  qmx);
    node_set_sym(o + 10u, qxx);
    node_set_sym(o + 16u, qmm);
    node_set_m3(o + 22u, qmx);
    node_set_v3(o + 31u, wx);
    node_set_v3(o + 34u, wm);
  }
}

// Node k of every system (its pivot and right-hand side are the two halves' parts, so both halves make it with the
// same arithmetic), then each half's back substitution towards its end: the solution u_v = (dx_v, mu_v) ends in node
// v's floats 31..36. After the barrier that follows the halves' eliminations.
void conservative_back_substitution(uint base, uint n, uint k, bool upper) {
  uint o = base + kNodeFloats * k, e = base + kNodeFloats * n;
  mat3 pxx, pmm, pmx;
  pivot_inverse(node_sym(o + 10u) - node_sym(e), node_m3(o + 22u) - node_m3(e + 12u),
                node_sym(o + 16u) + node_sym(e + 6u), pxx, pmm, pmx);
  vec3 rx = node_v3(e + 27u) - node_v3(e + 21u), rm = node_v3(e + 30u) - node_v3(e + 24u);
  vec3 ux = pxx * rx + transpose(pmx) * rm, um = pmx * rx + pmm * rm;  // u_k
  if (upper) {
    node_set_v3(o + 31u, ux);
    node_set_v3(o + 34u, um);
    // u_v = D_v^-1 (z_v - K(v+1, v)^T u_{v+1}), v = k - 1 .. 0
    for (uint v = k; v-- > 0u;) {
      o = base + kNodeFloats * v;
      mat3 gpn = node_m3(o + kNodeFloats);
      rx = node_v3(o + 31u) - transpose(gpn) * um;
      rm = node_v3(o + 34u) - s_blk[o + 9u] * ux;
      mat3 qmx = node_m3(o + 22u);
      ux = node_sym(o + 10u) * rx + transpose(qmx) * rm;
      um = qmx * rx + node_sym(o + 16u) * rm;
      node_set_v3(o + 31u, ux);
      node_set_v3(o + 34u, um);
    }
  } else {
    // u_v = E_v^-1 (w_v - K(v, v-1) u_{v-1}), v = k + 1 .. n - 1
    for (uint v = k + 1u; v < n; ++v) {
      o = base + kNodeFloats * v;
      rx = node_v3(o + 31u) - s_blk[o - kNodeFloats + 9u] * um;
      rm = node_v3(o + 34u) - node_m3(o) * ux;
      mat3 qmx = node_m3(o + 22u);
      ux = node_sym(o + 10u) * rx + transpose(qmx) * rm;
      um = qmx * rx + node_sym(o + 16u) * rm;
      node_set_v3(o + 31u, ux);
      node_set_v3(o + 34u, um);
    }
  }
}

// Which half of which strand's system this invocation solves (kLowerFirst, frame_lanes.glsl): base is the strand's
// first float, neither half for every other invocation.
struct SolverRole {
  bool upper, lower;
  uint base;
};
SolverRole solver_role() {
  const uint li = gl_LocalInvocationIndex;
  SolverRole r;
  r.upper = li < kSlots;
  r.lower = li >= kLowerFirst && li < kLowerFirst + kSlots;
  r.base = kSlotFloats * (r.upper ? li : li - kLowerFirst);
  return r;
}

// The workgroup's systems, one a strand (strands of at most 2 k + 2 nodes); called by every invocation (its barrier).
// The solution u_v = (dx_v, mu_v) ends in node v's floats 31..36.
void conservative_solve(uint n) {
  const SolverRole r = solver_role();
  const uint k = n / 2u;
  if (r.upper) solve_upper_half(r.base, n, k);
  else if (r.lower) solve_lower_half(r.base, n, k);
  barrier();
  if (r.upper || r.lower) conservative_back_substitution(r.base, n, k, r.upper);
}

// The same systems solved again with the factor conservative_solve left (D_v^-1 in floats 10..30, node k's two
// parts, the couplings in floats 0..9), for a right-hand side with both parts, (x, multiplier), in every node's
// floats 31..36; the solution ends there. No pivot is inverted but node k's.
void conservative_resolve(uint n) {
  const SolverRole r = solver_role();
  const uint base = r.base;
  const uint k = n / 2u;
  const uint e = base + kNodeFloats * n;
  if (r.upper) {
    // z_v = r_v - K(v, v-1) D_{v-1}^-1 z_{v-1}, v = 0 .. k (node k's part to the exchange, as solve_upper_half)
    mat3 pxx = mat3(0.0), pmm = mat3(0.0), pmx = mat3(0.0);
    vec3 zx = vec3(0.0), zm = vec3(0.0);
    float g = 0.0;
    for (uint v = 0u; v <= k; ++v) {
      uint o = base + kNodeFloats * v;
      vec3 yx = pxx * zx + transpose(pmx) * zm, ym = pmx * zx + pmm * zm;
      zx = node_v3(o + 31u) - g * ym;
      zm = node_v3(o + 34u) - node_m3(o) * yx;
      if (v == k) {
        node_set_v3(e + 27u, zx);
        node_set_v3(e + 30u, zm);
        break;
      }
      node_set_v3(o + 31u, zx);
      node_set_v3(o + 34u, zm);
      pxx = node_sym(o + 10u);
      pmm = node_sym(o + 16u);
      pmx = node_m3(o + 22u);
      g = s_blk[o + 9u];
    }
  } else if (r.lower) {
    // w_v = r_v - K(v, v+1) E_{v+1}^-1 w_{v+1}, v = n - 1 .. k (node k's part to the exchange, as solve_lower_half)
    mat3 qxx = mat3(0.0), qmm = mat3(0.0), qmx = mat3(0.0);
    vec3 wx = vec3(0.0), wm = vec3(0.0);
    for (uint v = n; v-- > k;) {
      uint o = base + kNodeFloats * v;
      mat3 gpn = v + 1u < n ? node_m3(base + kNodeFloats * min(v + 1u, n - 1u)) : mat3(0.0);  // Gp_{v+1}
      float g = s_blk[o + 9u];
      vec3 yx = qxx * wx + transpose(qmx) * wm, ym = qmx * wx + qmm * wm;
      if (v == k) {
        node_set_v3(e + 21u, transpose(gpn) * ym);
        node_set_v3(e + 24u, g * yx);
        break;
      }
      wx = node_v3(o + 31u) - transpose(gpn) * ym;
      wm = node_v3(o + 34u) - g * yx;
      node_set_v3(o + 31u, wx);
      node_set_v3(o + 34u, wm);
      qxx = node_sym(o + 10u);
      qmm = node_sym(o + 16u);
      qmx = node_m3(o + 22u);
    }
  }
  barrier();
  if (r.upper || r.lower) conservative_back_substitution(base, n, k, r.upper);
}

// The conservative local shape (the reference's local_shape_conservative, LengthModel::kConservative): the compliant
// model's constraints x_{v+1} - x_v - T_v with their full gradient, dT/de = ((T.u) I - u T^T) / |e| on the edge before
// (where that edge is the frame edge), so that every constraint touches x_{v-1}, x_v, x_{v+1}. The reference solves
// (G W G^T + a) dlambda = b, a = at / (1 + gamma), rows divided by 1 + gamma (3x3-block pentadiagonal), in double.
// In float that system cannot be formed: across a strand G is a second difference, G G^T a fourth, and its rounding
// alone (solved exactly after) moved a strand of 128 vertices at 60 Hz by 5e-3 of its length in one step (numpy;
// the GPU measured 2.3e-3 for long128, 3.8e-5 for Ratboy at 60 Hz, 4.3e-5 for the 128-vertex hard case). So the
// lanes write the same solution's quasi-definite form, [[W^-1, G^T], [G, -a]] (dx, -dlambda) = (0, b), ordered by
// vertex (dx_v with constraint v's multiplier): block-tridiagonal in 6x6 blocks, G never multiplied by itself. Two
// invocations solve each strand's system from its two ends (conservative_solve); dx_v is the lane's move. lavapipe:
// long128 at 60 Hz 2.3e-3 -> 2.9e-5, Ratboy at 60 Hz 3.3e-5 -> 3.4e-6; H100: hard cases 14 -> 15 of 15, at 2x the cost
// of the normal equations with one invocation a strand; the two-ended solve and the odd strand stride then made it
// faster than that (docs/accuracy.md).
// Its barriers need every invocation of the workgroup: the iterations run to the workgroup's most (tvk_iterations,
// main; a strand with fewer leaves the extra ones unapplied), and the lanes past the last guide run as the last guide
// (main, tvk_active).
void local_shape_lanes_conservative(uint g, uint v, LaneRest lr, GroupParams gp) {
  vec4 skin = skin_rotation(g);
  bool row = v >= 1u && v + 1u < N;
  float rel = row ? kCalibrationSegments * lr.len / strand_rest_length(g) : 0.0;
  float at = gp.reserved0 * kConservativeCalibration * rel * rel * rel * rel;
  float gm = row ? kConservativeDampingScale * gp.reserved1 * min(1.0 / (rel * rel), kBendDampingGrowthCap) : 0.0;
  // The vertex's weight: 0 pinned, 1 free, 1 - f where the global spring pulls it (the reference's shape_weight).
  float w_self = 0.0;
  if (v < N && L_pos.w > 0.0) {
    w_self = TVK_HAS(TVK_FEATURE_GLOBAL_SHAPE) && gp.global_stiffness > 0.0 && lr.arc <= gp.global_range
                 ? 1.0 - gp.global_stiffness
                 : 1.0;
  }
  const mat3 I3 = mat3(1.0);
  vec3 lam = vec3(0.0);
  vec3 rest_dir = quat_rotate(skin, lr.edge);
  // The head's turn of this step carries the vertex by this (about the anchor: the constraints see no translation);
  // the damped rate leaves it out, as the reference's local_shape_conservative does.
  const vec3 carried = quat_rotate_delta(skin_delta(g), L_prev.xyz);
  const uint node = kSlotFloats * tvk_slot_strand + kNodeFloats * v;  // this lane's node (lanes v < N only)
  for (uint it = 0u; it < tvk_iterations; ++it) {
    const bool apply = it < gp.local_iterations;
    // 1. Directions and targets, as local_shape_lanes; jf: the frame edge the target came from.
    ShapeTarget st = lanes_shape_target(v, lr, row, rest_dir);
    vec4 np = st.np;
    vec3 u = st.u, target = st.target;
    int jf = st.jf;
    // 2. The reaction's Jacobian, from the edge before (its direction and length) and this row's target.
    float elen = v + 1u < N ? length(np.xyz - L_pos.xyz) : 0.0;
    vec3 delta_self = L_pos.xyz - L_prev.xyz - carried;
    lanes_put(v, vec4(u, elen), vec4(delta_self, w_self), vec4(0.0));
    vec4 before0 = lanes_get0(lane_before(v));
    vec4 before1 = lanes_get1(lane_before(v));
    vec4 after1 = lanes_get1(lane_after(v));
    float w_prev = v >= 1u ? before1.w : 0.0;
    float w_next = v + 1u < N ? after1.w : 0.0;
    bool react = row && jf == int(v) - 1;
    mat3 J = mat3(0.0);
    if (react) J = (dot(target, before0.xyz) * I3 - outerProduct(before0.xyz, target)) / max(before0.w, 0.5 * lr.len_left);
    bool live = row && (w_self > 0.0 || w_next > 0.0 || (react && w_prev > 0.0)) && !isinf(at) && !isnan(at);
    vec3 rate = after1.xyz - delta_self - J * (delta_self - before1.xyz);
    vec3 rhs = live ? -(np.xyz - L_pos.xyz - target + at * lam + gm * rate) / (1.0 + gm) : vec3(0.0);
    // 3. This node: constraint v's gradient blocks on the free vertices (x_{v-1}: J, x_v: -I - J, x_{v+1}: I), the
    // vertex's M = 1 / w, the constraint's compliance. A constraint that is not there (the root, the tip, no free
    // vertex) is mu_v = 0: compliance 1, no coupling, no right-hand side.
    const mat3 gp_self = live && w_prev > 0.0 ? J : mat3(0.0);
    const float g_self = live && w_next > 0.0 ? 1.0 : 0.0;
    const float m_self = w_self > 0.0 ? 1.0 / w_self : 1.0;
    const float a_self = live ? at / (1.0 + gm) : 1.0;
    const mat3 gs_self = live && w_self > 0.0 ? -I3 - J : mat3(0.0);
    if (v < N) {
      node_set_m3(node, gp_self);
      s_blk[node + 9u] = g_self;
      s_blk[node + 10u] = m_self;
      s_blk[node + 11u] = a_self;
      node_set_m3(node + 12u, gs_self);
      node_set_v3(node + 21u, rhs);
    }
    barrier();
    conservative_solve(N);
    barrier();
    vec3 dx = vec3(0.0), mu = vec3(0.0);
    if (v < N) {
      dx = node_v3(node + 31u);
      mu = node_v3(node + 34u);
    }
    // 4. Below kConservativeRefineBelowHz (sim/fused.hpp, TVK_FEATURE_REFINE) iterative refinement, once (three times
    // below kConservativeRefineThriceBelowHz, TVK_FEATURE_REFINE_THRICE): the system's residual for the solution, each
    // lane its node's (its own blocks from registers, its neighbours' solution by the exchange and their couplings from
    // their nodes' floats 0..9, which the solve leaves as written), solved with the same factor and added. The factorisation in float loses digits on stiff strands, the more the
    // longer the step: at 60 Hz with 1 iteration the stiff strands, tight curls, extreme wind and strands pinned at
    // both ends missed the 1e-5 step-error bar on lavapipe (1.0e-5, 4.7e-5, 2.2e-5, 6.3e-5); with this solve made in
    // double (a diagnostic build) they read 1.2e-7, 2.0e-7, 1.6e-6 and 8.5e-8, and with the refinement in float
    // 1.4e-7, 2.2e-7, 2.3e-6 and 1.6e-7: the digits were the factorisation's.
    const uint refinements = TVK_HAS(TVK_FEATURE_REFINE) ? (TVK_HAS(TVK_FEATURE_REFINE_THRICE) ? 3u : 1u) : 0u;
    for (uint i = 0u; i < refinements; ++i) {
      lanes_put(v, vec4(dx, 0.0), vec4(mu, 0.0), vec4(0.0));
      vec3 dx_before = lanes_get0(lane_before(v)).xyz, mu_before = lanes_get1(lane_before(v)).xyz;
      vec3 dx_after = lanes_get0(lane_after(v)).xyz, mu_after = lanes_get1(lane_after(v)).xyz;
      if (v < N) {
        // (indices clamped into the strand: a select may read both sides)
        float g_before = v >= 1u ? s_blk[node - kNodeFloats * min(v, 1u) + 9u] : 0.0;
        mat3 gp_after = v + 1u < N ? node_m3(node + (v + 1u < N ? kNodeFloats : 0u)) : mat3(0.0);
        vec3 rx = -(m_self * dx + transpose(gs_self) * mu + g_before * mu_before + transpose(gp_after) * mu_after);
        vec3 rm = rhs - (gs_self * dx - a_self * mu + gp_self * dx_before + g_self * dx_after);
        node_set_v3(node + 31u, rx);
        node_set_v3(node + 34u, rm);
      }
      barrier();
      conservative_resolve(N);
      barrier();
      if (v < N) {
        dx += node_v3(node + 31u);
        mu += node_v3(node + 34u);
      }
    }
    // 5. The move and the multiplier come out of the solve: dx_v = W G^T dlambda, mu_v = -dlambda_v.
    vec3 dl = row && apply ? -mu : vec3(0.0);
    // This node is read here before this lane writes it again; the solver's next writes follow two barriers. The
    // root moves too where it is free (no pinned vertex: the first constraint's reaction on its frame edge reaches it).
    if (v < N && w_self > 0.0 && apply) L_pos = vec4(L_pos.xyz + dx, L_pos.w);
    if (row) lam += dl;
  }
}

void local_shape_lanes(uint g, uint v, LaneRest lr, GroupParams gp) {
  if (TVK_HAS(TVK_FEATURE_CONSERVATIVE)) {
    local_shape_lanes_conservative(g, v, lr, gp);
    return;
  }
  vec4 skin = skin_rotation(g);
  bool row = v >= 1u && v + 1u < N;
  float rel = row ? kCalibrationSegments * lr.len / strand_rest_length(g) : 0.0;
  float at = gp.reserved0 * rel * rel * rel;
  float gm = row ? gp.reserved1 * min(1.0 / (rel * rel), kBendDampingGrowthCap) : 0.0;
  vec3 lam = vec3(0.0);
  vec3 rest_dir = quat_rotate(skin, lr.edge);  // this lane's skinned rest edge
  for (uint it = 0u; it < gp.local_iterations; ++it) {
    // 1. Edge directions, then each constraint's target, as lanes_shape_target (written out here: calling it cost this
    // kernel 17-30 % on an NVIDIA H100 at 240 Hz, Ratboy 107.3 -> 127.2 us, 1 M 1,104 -> 1,382, 4 M 4,119 -> 5,354;
    // the driver's register choice for this kernel was later seen to follow the module's other code, 80 or 96
    // registers, docs/simulation.md, so that cost may be the same effect: not measured again).
    lanes_put(v, L_pos, L_prev, vec4(0.0));
    vec4 np = lanes_get0(lane_after(v));
    vec3 nq = lanes_get1(lane_after(v)).xyz;
    vec3 u = vec3(0.0);
    if (v + 1u < N) u = constraint_direction(np.xyz - L_pos.xyz, nq - L_prev.xyz, lr.len);
    bool turns_here = lr.turns && dot(u, u) > 0.0;
    vec4 turn = turns_here ? quat_from_two_unit(normalize(rest_dir), u) : vec4(0, 0, 0, 1);
    lanes_put(v, turn, vec4(turns_here ? 1.0 : 0.0, float(lr.frame_edge), 0.0, 0.0), vec4(0.0));
    vec4 q = vec4(0, 0, 0, 1);
    int j = row ? lr.frame_edge : -1;
    TVK_EXCHANGE_LOOP for (uint round = 0u; round < N; ++round) {
      uint src = j >= 0 ? uint(j) : v;
      vec4 qj = lanes_get0(src);
      vec4 info = lanes_get1(src);
      if (j >= 0) {
        if (info.x > 0.5) {
          q = qj;
          j = -1;
        } else {
          j = int(info.y);
        }
      }
      if (!lanes_any(v, j >= 0)) break;
    }
    vec3 target = row ? quat_rotate(q, rest_dir) : vec3(0.0);
    // 2. All constraints at once, the targets held.
    float ra = 0.0, rb = 1.0, rc = 0.0;
    vec3 rd = vec3(0.0);
    if (row) {
      float wa = L_pos.w > 0.0 ? 1.0 : 0.0, wb = np.w > 0.0 ? 1.0 : 0.0;
      if (wa + wb > 0.0) {
        vec3 c = np.xyz - L_pos.xyz - target;
        vec3 vel = (np.xyz - nq) - (L_pos.xyz - L_prev.xyz);
        ra = v > 1u ? -(1.0 + gm) * wa : 0.0;
        rc = v + 2u < N ? -(1.0 + gm) * wb : 0.0;
        rb = (1.0 + gm) * (wa + wb) + at;
        rd = -(c + at * lam + gm * vel);
      }
    }
    vec3 dl = lanes_tridiagonal_refined(v, ra, rb, rc, rd);
    lanes_put(v, vec4(dl, 0.0), vec4(0.0), vec4(0.0));
    vec3 before_dl = lanes_get0(lane_before(v)).xyz;
    if (v >= 1u && v < N && L_pos.w > 0.0) {
      vec3 before = v >= 2u ? before_dl : vec3(0.0);
      vec3 here = v + 1u < N ? dl : vec3(0.0);
      L_pos = vec4(L_pos.xyz + before - here, L_pos.w);
    }
    if (row) lam += dl;
  }
}

// One Newton step of every segment's length constraint (the reference's solve_lengths on the compliant model):
// lane v holds segment v (v < N - 1) and vertex v. move and lam accumulate the step's move (vertex) and multiplier
// (segment) for the transverse solve.
void newton_lanes(uint v, LaneRest lr, float reach_floor, float weight, inout vec3 move, inout float lam) {
  bool seg = v + 1u < N;
  lanes_put(v, L_pos, L_prev, vec4(0.0));
  vec4 np = lanes_get0(lane_after(v));
  vec3 nq = lanes_get1(lane_after(v)).xyz;
  vec3 gv = vec3(0.0);
  float rest = lr.len;
  if (seg) gv = constraint_direction(np.xyz - L_pos.xyz, nq - L_prev.xyz, rest);
  lanes_put(v, vec4(gv, 0.0), vec4(0.0), vec4(0.0));
  vec3 gl = lanes_get0(lane_before(v)).xyz;
  vec3 gr = lanes_get0(lane_after(v)).xyz;
  float ra = 0.0, rb = 1.0, rc = 0.0, rd = 0.0;
  if (seg) {
    float wa = L_pos.w > 0.0 ? 1.0 : 0.0, wb = np.w > 0.0 ? 1.0 : 0.0;
    if (wa + wb > 0.0 && dot(gv, gv) > 0.25) {
      rb = (wa + wb) * dot(gv, gv);
      rd = dot(np.xyz - L_pos.xyz, gv) - rest;
      ra = v > 0u ? -wa * dot(gv, gl) : 0.0;
      rc = v + 2u < N ? -wb * dot(gv, gr) : 0.0;
    }
  }
  float l = lanes_tridiagonal1(v, ra, rb, rc, rd);
  lanes_put(v, vec4(l, 0.0, 0.0, 0.0), vec4(0.0), vec4(0.0));
  float ll = lanes_get0(lane_before(v)).x;
  vec3 dx = vec3(0.0);
  float ratio = weight;
  if (v < N && L_pos.w > 0.0) {
    if (seg) dx += l * gv;
    if (v > 0u) dx -= ll * gl;
    // Against segments of at least kCompliantReachFloorRel of the mean segment (see the reference's solve_lengths).
    float reach = 0.5 * min(v > 0u ? max(lr.len_left, reach_floor) : 3.0e38, seg ? max(rest, reach_floor) : 3.0e38);
    float len = length(dx);
    if (len * weight > reach) ratio = reach / len;
  }
  float scale = lanes_min(v, ratio);
  if (v < N && L_pos.w > 0.0) {
    L_pos = vec4(L_pos.xyz + scale * dx, L_pos.w);
    move += scale * dx;
  }
  if (seg) lam += scale * l;
}

// The transverse response at the average-acceleration state (the reference's implicit_transverse, alpha 1/4).
void transverse_lanes(uint v, LaneRest lr, vec3 move, float lam) {
  const float alpha = 0.25;
  bool seg = v + 1u < N;
  bool vert = v < N;
  float ka = seg ? alpha * max(lam, 0.0) / lr.len : 0.0;
  vec3 c = vec3(0.0);
  if (vert) {
    vec3 x1 = L_pos.xyz;
    c = (1.0 / alpha) * (0.25 * x1 + 0.5 * L_prev.xyz + 0.25 * L_prevprev.xyz - (x1 - move));
  }
  lanes_put(v, vec4(c, ka), L_pos, vec4(0.0));
  vec4 left = lanes_get0(lane_before(v));
  vec3 right_c = lanes_get0(lane_after(v)).xyz;
  float wl = lanes_get1(lane_before(v)).w;
  float wr = lanes_get1(lane_after(v)).w;
  float kl = v > 0u && vert ? left.w : 0.0;
  float kr = seg ? ka : 0.0;
  float ra = 0.0, rb = 1.0, rc = 0.0;
  vec3 rd = vec3(0.0);
  if (vert && L_pos.w > 0.0) {
    if (v > 0u) rd -= kl * (c - left.xyz);
    if (seg) rd -= kr * (c - right_c);
    ra = v > 0u && wl > 0.0 ? -kl : 0.0;
    rc = seg && wr > 0.0 ? -kr : 0.0;
    rb = 1.0 + kl + kr;
  }
  vec3 delta = lanes_tridiagonal_refined(v, ra, rb, rc, rd);
  if (vert && L_pos.w > 0.0) L_pos = vec4(L_pos.xyz + delta, L_pos.w);
}

// How far segment v (the lane's, with a free end) is off its rest length, relative to it; 0 for the tip's lane.
float segment_off(uint v, LaneRest lr) {
  lanes_put(v, L_pos, vec4(0.0), vec4(0.0));
  vec4 np = lanes_get0(lane_after(v));
  return v + 1u < N && (L_pos.w > 0.0 || np.w > 0.0) ? abs(length(np.xyz - L_pos.xyz) - lr.len) / lr.len : 0.0;
}

// An extra Newton step's weight: how far over kCompliantStretchTol the strand's worst segment is, whole at twice it
// (as the reference: continuous in the state); settled where none is over it (no step).
float extra_newton_weight(uint v, LaneRest lr, out bool settled) {
  float worst = lanes_max(v, segment_off(v, lr));
  settled = !(worst > kCompliantStretchTol);
  return min((worst - kCompliantStretchTol) / kCompliantStretchTol, 1.0);
}

// The conservative model's length fallback (the reference's, after its extra Newton steps): where a segment is still
// off its length by more than kConservativeFallbackStretch, a follow-the-leader clean-up from the root, its move
// weighted from 0 there to whole at twice that; strands with a free tip only. The walk hands each cleaned vertex to
// the next lane, one round a vertex, on the strands that need it (the condition is the strand's, as the extra
// steps' is).
void length_fallback_lanes(uint v, LaneRest lr) {
  float off = segment_off(v, lr);
  if (v + 1u == N && !(L_pos.w > 0.0)) off = 3.0e38;  // a pinned tip: no fallback
  float worst = lanes_max(v, off);
  if (!(worst < 1.0e38)) return;
  float weight = clamp((worst - kConservativeFallbackStretch) / kConservativeFallbackStretch, 0.0, 1.0);
  if (!(weight > 0.0)) return;
  vec3 mine = L_pos.xyz, cleaned = L_pos.xyz;
  TVK_EXCHANGE_LOOP for (uint r = 1u; r < N; ++r) {
    lanes_put(v, vec4(cleaned, 0.0), vec4(0.0), vec4(0.0));
    vec3 parent = lanes_get0(lane_before(v)).xyz;
    if (v == r && L_pos.w > 0.0) {
      vec3 d = mine - parent;
      float l = length(d);
      if (l > 0.0) cleaned = parent + (lr.len_left / l) * d;
    }
  }
  if (v < N) L_pos = vec4(mine + weight * (cleaned - mine), L_pos.w);
}

void length_lanes(uint g, uint b, uint v, LaneRest lr, GroupParams gp, bool write_tangents) {
  bool vert = v < N;

  if (TVK_HAS(TVK_FEATURE_WIND)) {
    // As the serial pass, but every segment's direction from the positions before the wind (the reference's compliant
    // branch walks from the tip, so each parent is read before it is pushed).
    float a = float(g % 20u) / 20.0;
    vec3 w = a * (step_params[TVK_STEP].wind[0].xyz + step_params[TVK_STEP].wind[2].xyz) +
             (1.0 - a) * (step_params[TVK_STEP].wind[1].xyz + step_params[TVK_STEP].wind[3].xyz);
    lanes_put(v, L_pos, vec4(0.0), vec4(0.0));
    vec3 before = lanes_get0(lane_before(v)).xyz;
    if (vert && v > 0u && L_pos.w > 0.0) {
      vec3 e = L_pos.xyz - before;
      float len = length(e);
      vec3 push = w;
      if (len > kDirectionEps * lr.len_left) {
        vec3 t = e / len;
        push = w - dot(w, t) * t;
      }
      L_pos = vec4(L_pos.xyz + push, L_pos.w);
    }
  }

  // Every lane holds the anchor here (main), as collide_vertex reads it.
  if (TVK_HAS(TVK_FEATURE_COLLISION) && vert) collide_vertex(g, b, v);

  vec3 move = vec3(0.0);
  float lam = 0.0;
  float reach_floor = kCompliantReachFloorRel * strand_rest_length(g) / float(N - 1u);
  // The Newton steps: one, the transverse solve, length_iterations more, then up to kCompliantExtraNewton extra ones
  // while a segment is off by more than kCompliantStretchTol (extra_newton_weight).
  bool settled = false;  // the worst segment within kCompliantStretchTol: no extra step, no fallback
#ifdef TVK_LANES_SUBGROUP
  newton_lanes(v, lr, reach_floor, 1.0, move, lam);
  transverse_lanes(v, lr, move, lam);
  for (uint it = 0u; it < gp.length_iterations; ++it) newton_lanes(v, lr, reach_floor, 1.0, move, lam);
  for (uint extra = 0u; extra < kCompliantExtraNewton; ++extra) {
    float weight = extra_newton_weight(v, lr, settled);
    if (settled) break;
    newton_lanes(v, lr, reach_floor, weight, move, lam);
  }
#else
  // The same steps in one loop, so that the step's code and its barriers are there once: lavapipe compiles a
  // workgroup's barriers as coroutine suspensions, at a cost that grows with their number (with this loop and the
  // exchange loops kept, TVK_EXCHANGE_LOOP, the conservative model's 32-vertex pipelines compiled in 13-16 s instead
  // of 50). On an NVIDIA H100 the subgroup variant measured 8 % slower this way (the conservative model at 240 Hz,
  // Ratboy 227 -> 247 us), the shared-memory one the same.
  const uint plain = 1u + gp.length_iterations;
  TVK_EXCHANGE_LOOP for (uint k = 0u; k < plain + kCompliantExtraNewton; ++k) {
    float weight = 1.0;
    if (k >= plain) {
      weight = extra_newton_weight(v, lr, settled);
      if (settled) break;
    }
    newton_lanes(v, lr, reach_floor, weight, move, lam);
    if (k == 0u) transverse_lanes(v, lr, move, lam);
  }
#endif
  // (A strand the extra steps left within their tolerance is below the fallback's threshold as well: its reduction
  // runs only on strands that took every extra step.)
  if (TVK_HAS(TVK_FEATURE_CONSERVATIVE) && !settled) length_fallback_lanes(v, lr);

  finish_lanes(g, b, v, gp, write_tangents);
}

#endif
