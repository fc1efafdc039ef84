// The lane-parallel frame kernel of the compliant model (the reference's SimModel::kCompliant, docs/accuracy.md):
// one dispatch per frame runs every substep; one workgroup per guide, one lane per vertex (WORKGROUP_SIZE = the
// power of two >= N, so N up to 128), the strand's state in shared memory and a barrier between the steps, so it is
// correct for any subgroup size. Every per-substep solve is parallel over the lanes: the shape targets are local (one
// minimal rotation per edge), the local-shape and length systems are tridiagonal and solved by parallel cyclic
// reduction (log2 lanes steps), the damped Newton scale, the stretch test and the non-finite test are reductions. Integration and VSP are
// the per-vertex functions every path calls (integrate.glsl, vsp.glsl); the rest follows the reference's order
// (plugin/reference/src/simulator.cpp, local_shape_compliant and the kCompliant branch of length_and_collision).
// The host uploads the compliant constants in GroupParams: global_stiffness = the global spring's fraction at this h,
// reserved0 = the bending compliance alpha / h^2 at the calibration edge (31 edges per strand), reserved1 = the
// bending damping tau / h.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sim/layout.glsl"
layout(local_size_x_id = 0) in;

#define LANES WORKGROUP_SIZE

shared vec4 s_pos[N];
shared vec4 s_prev[N];
shared vec4 s_prevprev[N];
shared vec4 s_anchor;
// Scratch of the lane operations.
shared float s_a[LANES];
shared float s_b[LANES];
shared float s_c[LANES];
shared vec4 s_d[LANES];
shared vec4 s_x[LANES];
shared vec4 s_y[LANES];
shared float s_red[LANES];

uint tvk_frame_base;
uint tvk_step;
uint tvk_skin_base;
#define TVK_POS(i) s_pos[((i) - tvk_frame_base) / TVK_BLOCK]
#define TVK_PREV(i) s_prev[((i) - tvk_frame_base) / TVK_BLOCK]
#define TVK_PREVPREV(i) s_prevprev[((i) - tvk_frame_base) / TVK_BLOCK]
#define TVK_ANCHOR(g) s_anchor
#define TVK_STEP tvk_step
#define TVK_SKIN_BASE tvk_skin_base

#include "sim/integrate.glsl"
#include "sim/vsp.glsl"
#include "sim/length.glsl"
#include "sim/follow.glsl"

const float kCalibrationSegments = 31.0;
const uint kCompliantExtraNewton = 4u;
const float kCompliantStretchTol = 1e-3;
const float kCompliantReachFloorRel = 0.5;

// ---- lane operations (every lane of the workgroup calls them: they hold barriers) ---------------------------------

// Solves the tridiagonal system whose row r lane r holds (sub a, diagonal b, super c, right-hand side d; rows that are
// not part of the system are the identity) by parallel cyclic reduction; returns x_r.
vec3 lanes_tridiagonal(uint r, float a, float b, float c, vec3 d) {
  for (uint s = 1u; s < LANES; s <<= 1u) {
    s_a[r] = a;
    s_b[r] = b;
    s_c[r] = c;
    s_d[r] = vec4(d, 0.0);
    barrier();
    float a2 = 0.0, b2 = b, c2 = 0.0;
    vec3 d2 = d;
    if (r >= s) {
      float al = -a / s_b[r - s];
      a2 = al * s_a[r - s];
      b2 += al * s_c[r - s];
      d2 += al * s_d[r - s].xyz;
    }
    if (r + s < LANES) {
      float ga = -c / s_b[r + s];
      c2 = ga * s_c[r + s];
      b2 += ga * s_a[r + s];
      d2 += ga * s_d[r + s].xyz;
    }
    barrier();
    a = a2;
    b = b2;
    c = c2;
    d = d2;
  }
  return d / b;
}

// The same with one step of iterative refinement: the residual of the first solution (in float, from the lanes'
// neighbours) solved again and added. Parallel cyclic reduction's float error grows with the system's condition
// (~N^2 for the weakly diagonally dominant length and shape systems) times the solution, which carries the strand's
// whole load at low step rates; one refinement brings it back to rounding.
vec3 lanes_tridiagonal_refined(uint r, float a, float b, float c, vec3 d) {
  vec3 x = lanes_tridiagonal(r, a, b, c, d);
  s_y[r] = vec4(x, 0.0);
  barrier();
  vec3 res = d - b * x;
  if (r > 0u) res -= a * s_y[r - 1u].xyz;
  if (r + 1u < LANES) res -= c * s_y[r + 1u].xyz;
  barrier();
  return x + lanes_tridiagonal(r, a, b, c, res);
}

float lanes_max(uint r, float x) {
  s_red[r] = x;
  barrier();
  for (uint s = LANES / 2u; s > 0u; s >>= 1u) {
    if (r < s) s_red[r] = max(s_red[r], s_red[r + s]);
    barrier();
  }
  float m = s_red[0];
  barrier();
  return m;
}

float lanes_min(uint r, float x) { return -lanes_max(r, -x); }

// ---- the compliant model's passes ------------------------------------------------------------------------------------

float lane_weight(uint v) { return s_pos[v].w > 0.0 ? 1.0 : 0.0; }

// Rest edge k (vertex k to k + 1) of the strand at b in the asset's frame: rest_pos holds the root, then offsets from it.
vec3 lanes_rest_edge(uint b, uint k) {
  vec3 from = k == 0u ? vec3(0.0) : rest_pos[b + k * TVK_BLOCK].xyz;
  return rest_pos[b + (k + 1u) * TVK_BLOCK].xyz - from;
}

void local_shape_lanes(uint g, uint b, uint v) {
  GroupParams gp = guide_params(g);
  vec4 skin = skin_rotation(g);
  bool row = v >= 1u && v + 1u < N;
  float rel = row ? kCalibrationSegments * rest_info[b + v * TVK_BLOCK].x / strand_rest_length(g) : 0.0;
  float at = gp.reserved0 * rel * rel * rel;
  float gm = gp.reserved1;
  vec3 lam = vec3(0.0);
  for (uint it = 0u; it < gp.local_iterations; ++it) {
    // 1. Edge directions, then each constraint's target: its skinned rest edge turned by the minimal rotation of the
    // last edge before it that turns the frame, from that edge's skinned rest direction onto its current one.
    vec3 u = vec3(0.0);
    if (v + 1u < N) {
      u = constraint_direction(s_pos[v + 1u].xyz - s_pos[v].xyz, s_prev[v + 1u].xyz - s_prev[v].xyz,
                               rest_info[b + v * TVK_BLOCK].x);
    }
    s_x[v] = vec4(u, 0.0);
    barrier();
    vec3 target = vec3(0.0);
    if (row) {
      vec4 q = vec4(0, 0, 0, 1);
      for (uint j = v; j-- > 0u;) {
        vec3 uj = s_x[j].xyz;
        if (rest_info[b + (j + 1u) * TVK_BLOCK].z != 0.0 && dot(uj, uj) > 0.0) {
          q = quat_from_two_unit(normalize(quat_rotate(skin, lanes_rest_edge(b, j))), uj);
          break;
        }
      }
      target = quat_rotate(q, quat_rotate(skin, lanes_rest_edge(b, v)));
    }
    barrier();
    // 2. All constraints at once, the targets held.
    float ra = 0.0, rb = 1.0, rc = 0.0;
    vec3 rd = vec3(0.0);
    if (row) {
      float wa = lane_weight(v), wb = lane_weight(v + 1u);
      if (wa + wb > 0.0) {
        vec3 c = s_pos[v + 1u].xyz - s_pos[v].xyz - target;
        vec3 vel = (s_pos[v + 1u].xyz - s_prev[v + 1u].xyz) - (s_pos[v].xyz - s_prev[v].xyz);
        ra = v > 1u ? -(1.0 + gm) * wa : 0.0;
        rc = v + 2u < N ? -(1.0 + gm) * wb : 0.0;
        rb = (1.0 + gm) * (wa + wb) + at;
        rd = -(c + at * lam + gm * vel);
      }
    }
    vec3 dl = lanes_tridiagonal_refined(v, ra, rb, rc, rd);
    s_x[v] = vec4(dl, 0.0);
    barrier();
    if (v >= 1u && v < N && s_pos[v].w > 0.0) {
      vec3 before = v >= 2u ? s_x[v - 1u].xyz : vec3(0.0);
      vec3 here = v + 1u < N ? s_x[v].xyz : vec3(0.0);
      s_pos[v] = vec4(s_pos[v].xyz + before - here, s_pos[v].w);
    }
    if (row) lam += dl;
    barrier();
  }
}

// One Newton step of every segment's length constraint (the reference's solve_lengths on the compliant model):
// lane v holds segment v (v < N - 1) and vertex v. move and lam accumulate the step's move (vertex) and multiplier
// (segment) for the transverse solve.
void newton_lanes(uint b, uint v, float reach_floor, inout vec3 move, inout float lam) {
  bool seg = v + 1u < N;
  vec3 gv = vec3(0.0);
  float rest = seg ? rest_info[b + v * TVK_BLOCK].x : 0.0;
  if (seg) gv = constraint_direction(s_pos[v + 1u].xyz - s_pos[v].xyz, s_prev[v + 1u].xyz - s_prev[v].xyz, rest);
  s_x[v] = vec4(gv, 0.0);
  barrier();
  float ra = 0.0, rb = 1.0, rc = 0.0, rd = 0.0;
  if (seg) {
    float wa = lane_weight(v), wb = lane_weight(v + 1u);
    if (wa + wb > 0.0 && dot(gv, gv) > 0.25) {
      rb = (wa + wb) * dot(gv, gv);
      rd = dot(s_pos[v + 1u].xyz - s_pos[v].xyz, gv) - rest;
      ra = v > 0u ? -wa * dot(gv, s_x[v - 1u].xyz) : 0.0;
      rc = v + 2u < N ? -wb * dot(gv, s_x[v + 1u].xyz) : 0.0;
    }
  }
  float l = lanes_tridiagonal_refined(v, ra, rb, rc, vec3(rd, 0.0, 0.0)).x;
  s_red[v] = l;  // lanes_tridiagonal ended on a barrier; s_red is free
  barrier();
  vec3 dx = vec3(0.0);
  float ratio = 1.0;
  if (v < N && s_pos[v].w > 0.0) {
    if (seg) dx += l * gv;
    if (v > 0u) dx -= s_red[v - 1u] * s_x[v - 1u].xyz;
    // Against segments of at least kCompliantReachFloorRel of the mean segment (see the reference's solve_lengths).
    float reach = 0.5 * min(v > 0u ? max(rest_info[b + (v - 1u) * TVK_BLOCK].x, reach_floor) : 3.0e38,
                            seg ? max(rest, reach_floor) : 3.0e38);
    float len = length(dx);
    if (len > reach) ratio = reach / len;
  }
  barrier();
  float scale = lanes_min(v, ratio);
  if (v < N && s_pos[v].w > 0.0) {
    s_pos[v] = vec4(s_pos[v].xyz + scale * dx, s_pos[v].w);
    move += scale * dx;
  }
  if (seg) lam += scale * l;
  barrier();
}

// The transverse response at the average-acceleration state (the reference's implicit_transverse, alpha 1/4).
void transverse_lanes(uint b, uint v, vec3 move, float lam) {
  const float alpha = 0.25;
  bool seg = v + 1u < N;
  bool vert = v < N;
  s_a[v] = seg ? alpha * max(lam, 0.0) / rest_info[b + v * TVK_BLOCK].x : 0.0;
  vec3 c = vec3(0.0);
  if (vert) {
    vec3 x1 = s_pos[v].xyz;
    c = (1.0 / alpha) * (0.25 * x1 + 0.5 * s_prev[v].xyz + 0.25 * s_prevprev[v].xyz - (x1 - move));
  }
  s_x[v] = vec4(c, 0.0);
  barrier();
  float kl = v > 0u && vert ? s_a[v - 1u] : 0.0;
  float kr = seg ? s_a[v] : 0.0;
  float ra = 0.0, rb = 1.0, rc = 0.0;
  vec3 rd = vec3(0.0);
  if (vert && s_pos[v].w > 0.0) {
    if (v > 0u) rd -= kl * (c - s_x[v - 1u].xyz);
    if (seg) rd -= kr * (c - s_x[v + 1u].xyz);
    ra = v > 0u && s_pos[v - 1u].w > 0.0 ? -kl : 0.0;
    rc = seg && s_pos[v + 1u].w > 0.0 ? -kr : 0.0;
    rb = 1.0 + kl + kr;
  }
  barrier();
  vec3 delta = lanes_tridiagonal_refined(v, ra, rb, rc, rd);
  if (vert && s_pos[v].w > 0.0) s_pos[v] = vec4(s_pos[v].xyz + delta, s_pos[v].w);
  barrier();
}

void length_lanes(uint g, uint b, uint v, bool write_tangents) {
  GroupParams gp = guide_params(g);
  bool vert = v < N;
  vec4 p = vert ? s_pos[v] : vec4(0.0);

  if (TVK_HAS(TVK_FEATURE_WIND)) {
    // As the serial pass, but every segment's direction from the positions before the wind (the reference's compliant
    // branch walks from the tip, so each parent is read before it is pushed).
    float a = float(g % 20u) / 20.0;
    vec3 w = a * (step_params[TVK_STEP].wind[0].xyz + step_params[TVK_STEP].wind[2].xyz) +
             (1.0 - a) * (step_params[TVK_STEP].wind[1].xyz + step_params[TVK_STEP].wind[3].xyz);
    vec3 push = vec3(0.0);
    if (vert && v > 0u && p.w > 0.0) {
      vec3 e = p.xyz - s_pos[v - 1u].xyz;
      float len = length(e);
      push = w;
      if (len > kDirectionEps * rest_info[b + (v - 1u) * TVK_BLOCK].x) {
        vec3 t = e / len;
        push = w - dot(w, t) * t;
      }
    }
    barrier();
    if (vert && v > 0u && p.w > 0.0) {
      p = vec4(p.xyz + push, p.w);
      s_pos[v] = p;
    }
  }

  if (TVK_HAS(TVK_FEATURE_COLLISION) && vert && p.w > 0.0) {
    vec3 a = s_anchor.xyz;
    vec3 x = p.xyz;
    vec3 y = s_prev[v].xyz;
    bool hit = false;
    for (uint c = 0u; c < CAPSULE_COUNT; ++c) {
      vec4 c0 = step_params[TVK_STEP].capsule[2u * c];
      vec4 c1 = step_params[TVK_STEP].capsule[2u * c + 1u];
      c0.xyz -= a;
      c1.xyz -= a;
      vec3 m0 = step_params[TVK_STEP].capsule_move[2u * c].xyz;
      vec3 m1 = step_params[TVK_STEP].capsule_move[2u * c + 1u].xyz;
      vec3 axis = c1.xyz - c0.xyz;
      float aa = dot(axis, axis);
      float t = aa > 0.0 ? clamp(dot(x - c0.xyz, axis) / aa, 0.0, 1.0) : 0.0;
      vec3 centre = c0.xyz + t * axis;
      float radius = mix(c0.w, c1.w, t);
      vec3 d = x - centre;
      float dist = length(d);
      if (!(dist < radius)) continue;
      vec3 nrm;
      if (dist > kDirectionEps * radius) {
        nrm = d / dist;
      } else {
        vec3 back = y - centre;
        float bl = length(back);
        nrm = bl > kDirectionEps * radius ? back / bl : vec3(0, 1, 0);
      }
      float depth = radius - dist;
      x = centre + radius * nrm;
      float vn = dot((x - y) - (m0 + t * (m1 - m0)), nrm);
      if (vn < 0.0) y += min(depth / (kContactBand * radius), 1.0) * vn * nrm;
      hit = true;
    }
    if (hit) {
      s_pos[v] = vec4(x, p.w);
      s_prev[v] = vec4(y, p.w);
    }
  }
  barrier();

  vec3 move = vec3(0.0);
  float lam = 0.0;
  float reach_floor = kCompliantReachFloorRel * strand_rest_length(g) / float(N - 1u);
  newton_lanes(b, v, reach_floor, move, lam);
  transverse_lanes(b, v, move, lam);
  for (uint it = 0u; it < gp.length_iterations; ++it) newton_lanes(b, v, reach_floor, move, lam);
  for (uint extra = 0u; extra < kCompliantExtraNewton; ++extra) {
    float off = 0.0;
    if (v + 1u < N && (s_pos[v].w > 0.0 || s_pos[v + 1u].w > 0.0)) {
      float rest = rest_info[b + v * TVK_BLOCK].x;
      off = abs(length(s_pos[v + 1u].xyz - s_pos[v].xyz) - rest) / rest;
    }
    if (!(lanes_max(v, off) > kCompliantStretchTol)) break;
    newton_lanes(b, v, reach_floor, move, lam);
  }

  bool ok = true;
  if (vert) {
    p = s_pos[v];
    vec3 q = s_prev[v].xyz;
    if (TVK_HAS(TVK_FEATURE_MAX_SPEED) && gp.max_step > 0.0 && p.w > 0.0) {
      vec3 step = p.xyz - q;
      float len = length(step);
      if (len > gp.max_step) {
        q = p.xyz - step * (gp.max_step / len);
        s_prev[v] = vec4(q, p.w);
      }
    }
    ok = finite3(p.xyz) && finite3(q);
  }
  if (lanes_min(v, ok ? 1.0 : 0.0) < 0.5) {
    // As the serial pass: the rest pose, its history carried back by this step's rigid motion.
    vec3 q0 = s_prev[0].xyz;
    if (!finite3(q0)) q0 = vec3(0.0);
    barrier();
    if (vert) {
      vec4 back = skin_delta(g);
      back = vec4(-back.xyz, back.w);
      float inv_mass = strand_rigid(g, guide_params(g)) ? 0.0 : rest_pos[b + v * TVK_BLOCK].w;
      vec3 r = skin_offset(g, v);
      vec4 y = vec4(q0 + quat_rotate(back, r), inv_mass);
      s_pos[v] = vec4(r, inv_mass);
      s_prev[v] = y;
      s_prevprev[v] = y;
    }
    if (v == 0u) atomicAdd(counters[pc.counter_index], 1u);
    barrier();
  }

  if (write_tangents && vert) {
    // Along the edge leaving v (arriving for the tip); an edge too short to have a direction takes the tangent of the
    // nearest vertex before it that has one, the root the current root frame's +X.
    float min_len = kDirectionEps * strand_rest_length(g) / float(N - 1u);
    vec3 last = vec3(0.0);
    bool found = false;
    for (uint j = v + 1u; j-- > 0u;) {
      vec3 e = j + 1u < N ? s_pos[j + 1u].xyz - s_pos[j].xyz : s_pos[j].xyz - s_pos[j - 1u].xyz;
      float len = length(e);
      if (len > min_len) {
        last = e / len;
        found = true;
        break;
      }
    }
    if (!found) last = quat_rotate(current_root_frame(g), vec3(1, 0, 0));
    tangent[b + v * TVK_BLOCK] = vec4(last, 0.0);
  }
  barrier();
}

void main() {
  uint g = gl_WorkGroupID.x;
  uint v = gl_LocalInvocationID.x;
  if (g >= pc.guide_count || pc.step_count == 0u) return;  // uniform over the workgroup
  uint b = strand_base(g);
  tvk_frame_base = b;
  bool vert = v < N;
  uint i = b + v * TVK_BLOCK;
  if (vert) {
    s_pos[v] = pos[i];
    s_prev[v] = prev[i];
  }
  barrier();
  for (uint s = 0u; s < pc.step_count; ++s) {
    tvk_step = pc.step_index + s;
    tvk_skin_base = pc.skin_base + s * pc.skin_stride;
    if (vert) integrate_vertex(i, g, v);
    barrier();
    if (TVK_HAS(TVK_FEATURE_VSP)) {
      if (vert && v >= 1u) vsp_vertex(i, g, v);
      barrier();
    }
    if (TVK_HAS(TVK_FEATURE_LOCAL_SHAPE)) local_shape_lanes(g, b, v);
    length_lanes(g, b, v, s + 1u == pc.step_count);
  }
  if (vert) {
    pos[i] = s_pos[v];
    prev[i] = s_prev[v];
    if (TVK_HAS(TVK_FEATURE_VSP)) prevprev[i] = s_prevprev[v];
  }
  if (v == 0u) anchor[g] = s_anchor;

  if (K > 0u && vert) {
    float tip_separation = guide_params(g).tip_separation;
    uint G = pc.guide_count;
    for (uint f = 0u; f < K; ++f) {
      vec3 offset = follow_root_offset(g, f);
      uint dst = vertex_index(G + f * G + g, v);
      pos[dst] = follow_vertex(s_pos[v], offset, tip_separation, v);
      tangent[dst] = tangent[i];
    }
  }
}
