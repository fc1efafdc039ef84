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


// Solves the tridiagonal system whose row r lane r holds (sub a, diagonal b, super c, right-hand side d; rows that are
// not part of the system are the identity) by parallel cyclic reduction; returns x_r. Each step a lane publishes the
// reciprocal of its diagonal, so that it divides once. (Publishing the row divided by its diagonal instead exchanges
// two or four floats fewer a step: on an NVIDIA H100 3-9 % faster at 60 Hz, 0.6-5 % at 240 Hz, but Ratboy's step
// error at 60 Hz went from 1.2e-6 to 3.0e-6 of its length; not taken.) TVK_TRIDIAGONAL(name, T) makes the solver for a right-hand side
// of type T (float for the length rows, vec3 for the shape and transverse rows).
#define TVK_TRIDIAGONAL(name, T)                                                                                      \
  T name(uint r, float a, float b, float c, T d) {                                                                    \
    for (uint s = 1u; s < LANES; s <<= 1u) {                                                                          \
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
  for (uint round = 0u; round < N; ++round) {
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

// D(c) is inverted from its cofactors (one triangle: the block is symmetric). GLSL's inverse() here sent about one
// strand in ten of Ratboy and the straight groom out of control on lavapipe and the H100 alike, from the first frame;
// the cofactors of either triangle do not (not understood; the blocks were checked symmetric).
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

// One invocation per strand: the block LDL^T factorisation of the system in s_blk from row base (block row c holds
// A(c, c), A(c, c - 1), A(c, c - 2); they become D(c)^-1, L(c, c - 1), L(c, c - 2)) and the solve, s_vec = A^-1 s_vec.
// The recurrences run in registers over a window of two block rows, so a row costs a few 3x3 products and one 3x3
// inverse and the loads of the next row do not wait on them (a scalar banded Cholesky read from shared memory, its
// first form, spent most of its time waiting on those loads). The invocations 0 .. kSlots - 1 of the workgroup solve
// its strands' systems, one each, while the others wait at the barrier after it: with several strands a workgroup
// (the subgroup variant) the solves run side by side in one subgroup.
// NVIDIA H100, 240 / 60 Hz: Ratboy 5,242 -> 571 / 1,328 -> 161 us, curly 1 M 70,590 -> 7,327 / 17,752 -> 1,919 us.
// Block k (0: the diagonal block, then D^-1; 1: A(c, c - 1), then L(c, c - 1); 2: A(c, c - 2), then L(c, c - 2)) of
// block row r, and the row's vector.
mat3 blk_get(uint r, uint k) {
  uint o = 27u * r + 9u * k;
  return mat3(s_blk[o], s_blk[o + 1u], s_blk[o + 2u], s_blk[o + 3u], s_blk[o + 4u], s_blk[o + 5u], s_blk[o + 6u],
              s_blk[o + 7u], s_blk[o + 8u]);
}
void blk_set(uint r, uint k, mat3 a) {
  uint o = 27u * r + 9u * k;
  for (uint c = 0u; c < 3u; ++c)
    for (uint i = 0u; i < 3u; ++i) s_blk[o + 3u * c + i] = a[c][i];
}
vec3 vec_get(uint r) { return vec3(s_vec[3u * r], s_vec[3u * r + 1u], s_vec[3u * r + 2u]); }
void vec_set(uint r, vec3 x) {
  s_vec[3u * r] = x.x;
  s_vec[3u * r + 1u] = x.y;
  s_vec[3u * r + 2u] = x.z;
}

void block_solve(uint base, uint m) {
  mat3 di1 = mat3(0.0), di2 = mat3(0.0);  // D^-1 of rows c - 1, c - 2
  mat3 l1p = mat3(0.0);                   // L(c - 1, c - 2)
  vec3 z1 = vec3(0.0), z2 = vec3(0.0);    // z = L^-1 b of rows c - 1, c - 2
  for (uint c = 0u; c < m; ++c) {
    uint r = base + c;
    mat3 a1 = blk_get(r, 1u), a2 = blk_get(r, 2u);
    mat3 w1 = a1 - a2 * transpose(l1p);  // L(c, c - 1) D(c - 1)
    mat3 l2 = a2 * di2;
    mat3 l1 = w1 * di1;
    mat3 di = inverse_sym(blk_get(r, 0u) - l2 * transpose(a2) - l1 * transpose(w1));
    blk_set(r, 0u, di);
    blk_set(r, 1u, l1);
    blk_set(r, 2u, l2);
    vec3 z = vec_get(r) - l2 * z2 - l1 * z1;
    vec_set(r, z);
    di2 = di1;
    di1 = di;
    l1p = l1;
    z2 = z1;
    z1 = z;
  }
  vec3 x1 = vec3(0.0), x2 = vec3(0.0);  // x of rows c + 1, c + 2
  for (uint c = m; c-- > 0u;) {
    // (indices clamped into the strand's rows: a select may read both sides)
    mat3 u1 = c + 1u < m ? blk_get(base + min(c + 1u, m - 1u), 1u) : mat3(0.0);
    mat3 u2 = c + 2u < m ? blk_get(base + min(c + 2u, m - 1u), 2u) : mat3(0.0);
    vec3 x = blk_get(base + c, 0u) * vec_get(base + c) - transpose(u1) * x1 - transpose(u2) * x2;
    vec_set(base + c, x);
    x2 = x1;
    x1 = x;
  }
}

// The conservative local shape (the reference's local_shape_conservative, LengthModel::kConservative): the compliant
// model's constraints x_{v+1} - x_v - T_v with their full gradient, dT/de = ((T.u) I - u T^T) / |e| on the edge before
// (where that edge is the frame edge), so that every constraint touches x_{v-1}, x_v, x_{v+1} and the system
// (G W G^T + at / (1 + gamma), rows divided by 1 + gamma) is 3x3-block pentadiagonal. Each lane assembles its row's
// three blocks left of the diagonal from its neighbours' and writes them to shared memory; one invocation solves each
// strand's system (LDL^T, block_solve); the lanes then move their vertex by W G^T dlambda.
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
  const uint base = tvk_slot_strand * (N - 2u);
  const uint own = base + (v >= 1u ? v - 1u : 0u);  // this lane's row (row lanes only)
  for (uint it = 0u; it < tvk_iterations; ++it) {
    const bool apply = it < gp.local_iterations;
    // 1. Directions and targets, as local_shape_lanes; jf: the frame edge the target came from.
    ShapeTarget st = lanes_shape_target(v, lr, row, rest_dir);
    vec4 np = st.np;
    vec3 u = st.u, target = st.target;
    int jf = st.jf;
    // 2. The reaction's Jacobian, from the edge before (its direction and length) and this row's target.
    float elen = v + 1u < N ? length(np.xyz - L_pos.xyz) : 0.0;
    lanes_put(v, vec4(u, elen), vec4(L_pos.xyz - L_prev.xyz, w_self), vec4(0.0));
    vec4 before0 = lanes_get0(lane_before(v));
    vec4 before1 = lanes_get1(lane_before(v));
    vec4 after1 = lanes_get1(lane_after(v));
    float w_prev = v >= 1u ? before1.w : 0.0;
    float w_next = v + 1u < N ? after1.w : 0.0;
    bool react = row && jf == int(v) - 1;
    mat3 J = mat3(0.0);
    if (react) J = (dot(target, before0.xyz) * I3 - outerProduct(before0.xyz, target)) / max(before0.w, 0.5 * lr.len_left);
    bool live = row && (w_self > 0.0 || w_next > 0.0 || (react && w_prev > 0.0)) && !isinf(at) && !isnan(at);
    vec3 delta_self = L_pos.xyz - L_prev.xyz;
    vec3 rate = after1.xyz - delta_self - J * (delta_self - before1.xyz);
    vec3 rhs = live ? -(np.xyz - L_pos.xyz - target + at * lam + gm * rate) / (1.0 + gm) : vec3(0.0);
    // 3. This row's blocks: D0 (v, v), D1 (v, v - 1), D2 (v, v - 2); the rows before it from their lanes.
    lanes_put(v, vec4(J[0], live ? 1.0 : 0.0), vec4(J[1], 0.0), vec4(J[2], 0.0));
    vec4 jb0 = lanes_get0(lane_before(v));
    mat3 Jp = mat3(jb0.xyz, lanes_get1(lane_before(v)).xyz, lanes_get2(lane_before(v)).xyz);
    bool live_1 = v >= 2u && jb0.w > 0.5;
    // (every lane gets, then selects: in the subgroup variant a shuffle needs its source lane active, and a get under
    // a condition runs on some lanes only)
    vec4 jb2 = lanes_get0(v >= 2u ? v - 2u : 0u);
    bool live_2 = v >= 3u && jb2.w > 0.5;
    mat3 D0 = I3, D1 = mat3(0.0), D2 = mat3(0.0);
    if (live) {
      D0 = w_next * I3 + w_self * (I3 + J) * transpose(I3 + J) + w_prev * J * transpose(J) + (at / (1.0 + gm)) * I3;
      if (live_1) D1 = -w_self * (I3 + J) - w_prev * J * (I3 + transpose(Jp));
      if (live_2) D2 = w_prev * J;
    }
    if (row) {
      blk_set(own, 0u, D0);
      blk_set(own, 1u, D1);
      blk_set(own, 2u, D2);
      vec_set(own, rhs);
    }
    barrier();
    if (gl_LocalInvocationIndex < kSlots) block_solve(gl_LocalInvocationIndex * (N - 2u), N - 2u);
    barrier();
    // 4. No refinement: block LDL^T of this symmetric positive definite system is backward stable, and a refinement
    // step (the residual from the lanes' blocks, solved again) changed no step error (lavapipe: Ratboy 60 Hz 3.4e-5
    // with it, 3.3e-5 without; 240 Hz 1.8e-6 / 1.2e-6; two refinements 4.1e-5).
    vec3 dl = row && apply ? vec_get(own) : vec3(0.0);
    // Row own is read here before this lane writes it again; the solver's next writes follow two barriers.
    // 5. x += W G^T dlambda: rows v - 1 (I), v (-I - J_v), v + 1 (J_{v+1}).
    lanes_put(v, vec4(dl, 0.0), vec4(transpose(J) * dl, 0.0), vec4(0.0));
    vec3 dl_before = lanes_get0(lane_before(v)).xyz;
    vec3 react_after = lanes_get1(lane_after(v)).xyz;
    if (v >= 1u && v < N && w_self > 0.0 && apply) {
      vec3 move = (v >= 2u ? dl_before : vec3(0.0)) - dl - transpose(J) * dl + (v + 2u < N ? react_after : vec3(0.0));
      L_pos = vec4(L_pos.xyz + w_self * move, L_pos.w);
    }
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
    // kernel 17-30 % on an NVIDIA H100 at 240 Hz, Ratboy 107.3 -> 127.2 us, 1 M 1,104 -> 1,382, 4 M 4,119 -> 5,354).
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
    for (uint round = 0u; round < N; ++round) {
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
  newton_lanes(v, lr, reach_floor, 1.0, move, lam);
  transverse_lanes(v, lr, move, lam);
  for (uint it = 0u; it < gp.length_iterations; ++it) newton_lanes(v, lr, reach_floor, 1.0, move, lam);
  for (uint extra = 0u; extra < kCompliantExtraNewton; ++extra) {
    lanes_put(v, L_pos, vec4(0.0), vec4(0.0));
    vec4 np = lanes_get0(lane_after(v));
    float off = 0.0;
    if (v + 1u < N && (L_pos.w > 0.0 || np.w > 0.0)) off = abs(length(np.xyz - L_pos.xyz) - lr.len) / lr.len;
    // Weighted by how far over the tolerance the worst segment is, as the reference (continuous in the state).
    float worst = lanes_max(v, off);
    if (!(worst > kCompliantStretchTol)) break;
    newton_lanes(v, lr, reach_floor, min((worst - kCompliantStretchTol) / kCompliantStretchTol, 1.0), move, lam);
  }

  finish_lanes(g, b, v, gp, write_tangents);
}

#endif
