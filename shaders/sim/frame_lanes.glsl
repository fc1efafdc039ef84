// The lane-parallel frame kernel of the compliant model (the reference's SimModel::kCompliant, docs/accuracy.md):
// one dispatch per frame runs every substep, one lane per vertex. Every per-substep solve is parallel over the lanes:
// the shape targets are local (one minimal rotation per edge), the local-shape and length systems are tridiagonal and
// solved by parallel cyclic reduction (log2 lanes steps), the damped Newton scale, the stretch test and the
// non-finite test are reductions. Integration and VSP are the per-vertex functions every path calls (integrate.glsl,
// vsp.glsl); the rest follows the reference's order (plugin/reference/src/simulator.cpp, local_shape_compliant and
// the kCompliant branch of length_and_collision).
//
// Each lane keeps its vertex's state (position, history, VSP's second history) and its rest data in registers for the
// whole frame; lanes see each other's values only through the exchange below, which has two backends:
//   frame_lanes_subgroup.comp (TVK_LANES_SUBGROUP): a strand is a cluster of LANES consecutive invocations of one
//     subgroup (LANES = the power of two >= N, so the host uses it where the subgroup holds LANES lanes: N <= 32 on
//     NVIDIA); values move by subgroup shuffles, with no shared memory and no barrier; a workgroup holds
//     WORKGROUP_SIZE / LANES strands.
//   frame_lanes.comp: one strand per workgroup of LANES = WORKGROUP_SIZE invocations (any subgroup size, N up to 128);
//     values move through shared memory between barriers.
// Both run the same arithmetic in the same order.
// An exchange is lanes_put (every lane publishes up to three values), lanes_get* (any lane's published value, called
// by every lane of the strand: shuffles need their source active), valid until the next lanes_put.
//
// The host uploads the compliant constants in GroupParams: global_stiffness = the global spring's fraction at this h,
// reserved0 = the bending compliance alpha / h^2 at the calibration edge (31 edges per strand), reserved1 = the
// bending damping tau / h.
#ifdef TVK_LANES_SUBGROUP
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_shuffle : require
#extension GL_KHR_shader_subgroup_vote : require
#endif
#include "sim/layout.glsl"
layout(local_size_x_id = 0) in;

#ifdef TVK_LANES_SUBGROUP
// The power of two >= N (N <= 128: three shifts fold every bit below the highest one), as specialisation arithmetic.
const uint kLanesM1 = N - 1u;
const uint kLanesA = kLanesM1 | (kLanesM1 >> 1u);
const uint kLanesB = kLanesA | (kLanesA >> 2u);
const uint kLanesC = kLanesB | (kLanesB >> 4u);
#define LANES (kLanesC + 1u)
#else
#define LANES WORKGROUP_SIZE
#endif

// The lane's vertex state; integrate.glsl and vsp.glsl touch only their own vertex (i is always this lane's).
vec4 L_pos;
vec4 L_prev;
vec4 L_prevprev;
vec4 L_anchor;  // written by lane 0's integration; every lane's copy of it where the collisions need it
uint tvk_step;
uint tvk_skin_base;
#define TVK_POS(i) L_pos
#define TVK_PREV(i) L_prev
#define TVK_PREVPREV(i) L_prevprev
#define TVK_ANCHOR(g) L_anchor
#define TVK_STEP tvk_step
#define TVK_SKIN_BASE tvk_skin_base

#include "sim/integrate.glsl"
#include "sim/vsp.glsl"
#include "sim/length.glsl"  // finite3, constraint_direction, collide_vertex (its per-strand walks are not called here)
#include "sim/follow.glsl"

const float kCalibrationSegments = 31.0;
const uint kCompliantExtraNewton = 4u;
const float kCompliantStretchTol = 1e-3;
const float kCompliantReachFloorRel = 0.5;

// ---- the exchange ------------------------------------------------------------------------------------------------

#ifdef TVK_LANES_SUBGROUP
uint tvk_lane_base;  // the subgroup invocation of the strand's lane 0
vec4 tvk_put0, tvk_put1, tvk_put2;
void lanes_put(uint r, vec4 a, vec4 b, vec4 c) {
  tvk_put0 = a;
  tvk_put1 = b;
  tvk_put2 = c;
}
vec4 lanes_get0(uint src) { return subgroupShuffle(tvk_put0, tvk_lane_base + src); }
vec4 lanes_get1(uint src) { return subgroupShuffle(tvk_put1, tvk_lane_base + src); }
vec4 lanes_get2(uint src) { return subgroupShuffle(tvk_put2, tvk_lane_base + src); }
// Over the strand's lanes (a butterfly inside its cluster of LANES invocations).
// NaN counts as +infinity in both backends' reductions, so that every lane of a strand gets the same answer.
float lanes_max(uint r, float x) {
  x = isnan(x) ? uintBitsToFloat(0x7f800000u) : x;
  for (uint m = LANES / 2u; m > 0u; m >>= 1u) x = max(x, subgroupShuffleXor(x, m));
  return x;
}
// Loop control: true when any lane of the subgroup (so of every strand in it) still wants another round.
bool lanes_any(uint r, bool x) { return subgroupAny(x); }
#else
// Two slots per lane, used in turn: a lane writes a slot again only after the barrier of the exchange in between,
// which every lane reaches after its reads of the slot's last exchange, so reads need no barrier after them.
shared vec4 s_put0[2u * LANES];
shared vec4 s_put1[2u * LANES];
shared vec4 s_put2[2u * LANES];
shared float s_red[LANES];
uint tvk_slot = 0u;
void lanes_put(uint r, vec4 a, vec4 b, vec4 c) {
  tvk_slot ^= LANES;
  s_put0[tvk_slot + r] = a;
  s_put1[tvk_slot + r] = b;
  s_put2[tvk_slot + r] = c;
  barrier();
}
vec4 lanes_get0(uint src) { return s_put0[tvk_slot + src]; }
vec4 lanes_get1(uint src) { return s_put1[tvk_slot + src]; }
vec4 lanes_get2(uint src) { return s_put2[tvk_slot + src]; }
float lanes_max(uint r, float x) {
  s_red[r] = isnan(x) ? uintBitsToFloat(0x7f800000u) : x;
  barrier();
  for (uint s = LANES / 2u; s > 0u; s >>= 1u) {
    if (r < s) s_red[r] = max(s_red[r], s_red[r + s]);
    barrier();
  }
  float m = s_red[0];
  barrier();
  return m;
}
bool lanes_any(uint r, bool x) { return lanes_max(r, x ? 1.0 : 0.0) > 0.5; }
#endif

float lanes_min(uint r, float x) { return -lanes_max(r, -x); }
// The neighbours' lanes, clamped into the strand (a clamped read is never used).
uint lane_before(uint r) { return r > 0u ? r - 1u : 0u; }
uint lane_after(uint r) { return r + 1u < LANES ? r + 1u : r; }

vec4 to4(vec3 x) { return vec4(x, 0.0); }
vec4 to4(float x) { return vec4(x, 0.0, 0.0, 0.0); }
void unpack4(vec4 v, out vec3 x) { x = v.xyz; }
void unpack4(vec4 v, out float x) { x = v.x; }

// Solves the tridiagonal system whose row r lane r holds (sub a, diagonal b, super c, right-hand side d; rows that are
// not part of the system are the identity) by parallel cyclic reduction; returns x_r. Each step a lane publishes the
// reciprocal of its diagonal, so that it divides once. TVK_TRIDIAGONAL(name, T) makes the solver for a right-hand side
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
// is already at rounding level measured slower on NVIDIA: the test costs a reduction per solve.)
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
TVK_TRIDIAGONAL_REFINED(lanes_tridiagonal_refined1, lanes_tridiagonal1, float)

// ---- the lane's rest data, read once per frame ----------------------------------------------------------------------

struct LaneRest {
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

void local_shape_lanes(uint g, uint v, LaneRest lr, GroupParams gp) {
  vec4 skin = skin_rotation(g);
  bool row = v >= 1u && v + 1u < N;
  float rel = row ? kCalibrationSegments * lr.len / strand_rest_length(g) : 0.0;
  float at = gp.reserved0 * rel * rel * rel;
  float gm = gp.reserved1;
  vec3 lam = vec3(0.0);
  vec3 rest_dir = quat_rotate(skin, lr.edge);  // this lane's skinned rest edge
  for (uint it = 0u; it < gp.local_iterations; ++it) {
    // 1. Edge directions, then each constraint's target: its skinned rest edge turned by the minimal rotation of the
    // last edge before it that turns the frame, from that edge's skinned rest direction onto its current one. Each
    // lane makes the rotation of its own edge; a lane takes the one of its frame edge, or of the frame edge before
    // that while an edge is too short to have a direction.
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
  float l = lanes_tridiagonal_refined1(v, ra, rb, rc, rd);
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

  bool ok = true;
  if (vert) {
    vec3 q = L_prev.xyz;
    if (TVK_HAS(TVK_FEATURE_MAX_SPEED) && gp.max_step > 0.0 && L_pos.w > 0.0) {
      vec3 step = L_pos.xyz - q;
      float len = length(step);
      if (len > gp.max_step) {
        q = L_pos.xyz - step * (gp.max_step / len);
        L_prev = vec4(q, L_pos.w);
      }
    }
    ok = finite3(L_pos.xyz) && finite3(q);
  }
  if (lanes_min(v, ok ? 1.0 : 0.0) < 0.5) {
    // As the serial pass: the rest pose, its history carried back by this step's rigid motion.
    lanes_put(v, L_prev, vec4(0.0), vec4(0.0));
    vec3 q0 = lanes_get0(0u).xyz;
    if (!finite3(q0)) q0 = vec3(0.0);
    if (vert) {
      vec4 back = skin_delta(g);
      back = vec4(-back.xyz, back.w);
      float inv_mass = strand_rigid(g, gp) ? 0.0 : rest_pos[b + v * TVK_BLOCK].w;
      vec3 r = skin_offset(g, v);
      vec4 y = vec4(q0 + quat_rotate(back, r), inv_mass);
      L_pos = vec4(r, inv_mass);
      L_prev = y;
      L_prevprev = y;
    }
    if (v == 0u) atomicAdd(counters[pc.counter_index], 1u);
  }

  if (write_tangents) {
    // Along the edge leaving v (arriving for the tip); an edge too short to have a direction takes the tangent of the
    // nearest vertex before it that has one, the root the current root frame's +X.
    float min_len = kDirectionEps * strand_rest_length(g) / float(N - 1u);
    lanes_put(v, L_pos, vec4(0.0), vec4(0.0));
    vec3 after = lanes_get0(lane_after(v)).xyz;
    vec3 before = lanes_get0(lane_before(v)).xyz;
    vec3 e = v + 1u < N ? after - L_pos.xyz : L_pos.xyz - before;
    float len = length(e);
    bool has = vert && len > min_len;
    lanes_put(v, vec4(has ? e / len : vec3(0.0), has ? 1.0 : 0.0), vec4(0.0), vec4(0.0));
    vec3 last = vec3(0.0);
    bool found = false;
    int j = vert ? int(v) : -1;
    for (uint round = 0u; round < N; ++round) {
      vec4 t = lanes_get0(j >= 0 ? uint(j) : v);
      if (j >= 0) {
        if (t.w > 0.5) {
          last = t.xyz;
          found = true;
          j = -1;
        } else {
          --j;
        }
      }
      if (!lanes_any(v, j >= 0)) break;
    }
    if (vert) {
      if (!found) last = quat_rotate(current_root_frame(g), vec3(1, 0, 0));
      tangent[b + v * TVK_BLOCK] = vec4(last, 0.0);
    }
  }
}

void main() {
#ifdef TVK_LANES_SUBGROUP
  // Strands are clusters of LANES invocations of a subgroup; the host makes WORKGROUP_SIZE a multiple of the
  // subgroup size and the subgroup size a multiple of LANES, so that the subgroups are full (Vulkan would allow
  // partial ones without VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT, which needs a device feature the
  // host may not have enabled; no implementation we know launches them for such a workgroup) and this numbering
  // covers every strand of the workgroup once.
  uint v = gl_SubgroupInvocationID & (LANES - 1u);
  tvk_lane_base = gl_SubgroupInvocationID - v;
  uint g = gl_WorkGroupID.x * (WORKGROUP_SIZE / LANES) + (gl_SubgroupID * gl_SubgroupSize + tvk_lane_base) / LANES;
#else
  uint v = gl_LocalInvocationID.x;
  uint g = gl_WorkGroupID.x;
#endif
  if (g >= pc.guide_count || pc.step_count == 0u) return;  // uniform over the strand's lanes
  uint b = strand_base(g);
  bool vert = v < N;
  uint i = b + v * TVK_BLOCK;
  L_pos = vec4(0.0);
  L_prev = vec4(0.0);
  L_prevprev = vec4(0.0);
  L_anchor = vec4(0.0);
  if (vert) {
    L_pos = pos[i];
    L_prev = prev[i];
  }
  LaneRest lr = lane_rest(b, v);
  GroupParams gp = guide_params(g);
  for (uint s = 0u; s < pc.step_count; ++s) {
    tvk_step = pc.step_index + s;
    tvk_skin_base = pc.skin_base + s * pc.skin_stride;
    if (vert) integrate_vertex(i, g, v);
    // The anchor for the collisions (lane 0 integrated it), the roots' state for VSP.
    if (TVK_HAS(TVK_FEATURE_COLLISION)) {
      lanes_put(v, L_anchor, vec4(0.0), vec4(0.0));
      L_anchor = lanes_get0(0u);
    }
    if (TVK_HAS(TVK_FEATURE_VSP)) {
      lanes_put(v, L_pos, L_prev, L_prevprev);
      vec4 x0 = lanes_get0(0u), x1 = lanes_get0(1u);
      vec3 y0 = lanes_get1(0u).xyz, y1 = lanes_get1(1u).xyz;
      vec3 z0 = lanes_get2(0u).xyz, z1 = lanes_get2(1u).xyz;
      if (vert && v >= 1u && L_pos.w > 0.0) vsp_vertex_of(vsp_strand_from(g, x0, x1, y0, y1, z0, z1), i, v);
    }
    if (TVK_HAS(TVK_FEATURE_LOCAL_SHAPE)) local_shape_lanes(g, v, lr, gp);
    length_lanes(g, b, v, lr, gp, s + 1u == pc.step_count);
  }
  if (vert) {
    pos[i] = L_pos;
    prev[i] = L_prev;
    if (TVK_HAS(TVK_FEATURE_VSP)) prevprev[i] = L_prevprev;
  }
  if (v == 0u) anchor[g] = L_anchor;

  if (K > 0u && vert) {
    float tip_separation = gp.tip_separation;
    uint G = pc.guide_count;
    for (uint f = 0u; f < K; ++f) {
      vec3 offset = follow_root_offset(g, f);
      uint dst = vertex_index(G + f * G + g, v);
      pos[dst] = follow_vertex(L_pos, offset, tip_separation, v);
      tangent[dst] = tangent[i];
    }
  }
}
