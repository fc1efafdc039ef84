// The run kernel of the follow-the-leader model: one dispatch per frame runs every substep, each lane holding a run of
// RUN consecutive vertices of a strand in registers (a strand of N vertices is a cluster of RL lanes of one subgroup,
// RL = the power of two >= ceil(N / RUN); 32 vertices in runs of 8: 4 lanes, 8 strands per 32-lane subgroup).
//
// Between the one-thread kernel (frame.glsl: a strand's every step in one thread, its state in the GPU's local memory)
// and the lane kernel (frame_lanes.glsl: one vertex per lane, whose serial walks cost every lane of the strand): here
// the per-vertex phases (integration, VSP, collision, the finish, the follows) are RL-way parallel within a strand,
// and a serial walk runs in rounds: in round r lane r steps its RUN vertices from registers, and the walk's state
// crosses to the next lane once per round (a subgroup shuffle), so the walks' instructions are shared by the
// subgroup's 32 / RL strands. Local shape runs its iterations in pairs, the second walk one round (one lane) behind
// the first, so that each of its steps reads vertex v + 1 as the first walk left it. Every step is the one-thread
// kernel's arithmetic in its order (local_shape_step's, wind_step's, sweep_step), so both give the same float results.
//
// The per-lane arrays are indexed by constants only, so they stay in registers: the unrolled run loops' (the state
// macros below read tvk_k, which each unrolled iteration sets), or index 0, 1 and RUN - 1 of local shape's loop, which
// turns the run instead (turn_run_shape). Strands pinned at their tip take the one-thread kernel (the host chooses).
// The host uses this kernel where RL lanes fit the smallest subgroup the device may run and compute shaders shuffle.
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_shuffle : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_EXT_control_flow_attributes : require
#include "sim/layout.glsl"
layout(local_size_x_id = 0) in;

layout(constant_id = 5) const uint RUN = 8u;  // vertices per lane: 4 or 8 (the host chooses by groom size)
// The power of two >= ceil(N / RUN) (N <= 128: at most 32 lanes), as specialisation arithmetic.
const uint kRunsM1 = (N + RUN - 1u) / RUN - 1u;
const uint kRunsA = kRunsM1 | (kRunsM1 >> 1u);
const uint kRunsB = kRunsA | (kRunsA >> 2u);
const uint kRunsC = kRunsB | (kRunsB >> 4u);
#define RL (kRunsC + 1u)

vec4 R_pos[RUN];
vec4 R_prev[RUN];
vec4 R_prevprev[RUN];
vec4 R_anchor;  // written by the root's integration (lane 0); every lane's copy where the collisions need it
uint tvk_k;     // the run index the pass functions' state macros address
uint tvk_step;
uint tvk_skin_base;
#define TVK_POS(i) R_pos[tvk_k]
#define TVK_PREV(i) R_prev[tvk_k]
#define TVK_PREVPREV(i) R_prevprev[tvk_k]
#define TVK_ANCHOR(g) R_anchor
#define TVK_STEP tvk_step
#define TVK_SKIN_BASE tvk_skin_base

#include "sim/integrate.glsl"
#include "sim/vsp.glsl"
#include "sim/length.glsl"  // finite3, collide_vertex, sweep_step (not its per-strand walks)
#include "sim/follow.glsl"

uint tvk_lane_base;  // the subgroup invocation of the strand's lane 0
uint tvk_r;          // this lane's run: vertices tvk_r * RUN + k
vec4 from_lane(vec4 x, uint r) { return subgroupShuffle(x, tvk_lane_base + r); }
vec4 from_before(vec4 x) { return from_lane(x, tvk_r > 0u ? tvk_r - 1u : 0u); }
vec4 from_after(vec4 x) { return from_lane(x, tvk_r + 1u < RL ? tvk_r + 1u : tvk_r); }
float runs_min(float x) {
  for (uint m = RL / 2u; m > 0u; m >>= 1u) x = min(x, subgroupShuffleXor(x, m));
  return x;
}
uint vtx(uint k) { return tvk_r * RUN + k; }

// The run's rest data, read once per frame.
float R_len[RUN];  // rest length of the edge leaving vertex k (0 for the tip)
vec3 R_edge[RUN];  // the edge leaving vertex k at rest, in the frame local shape carries
uint R_turns;      // bit k: local shape turns its frame onto the edge arriving at vertex k
float R_len_in;    // rest length of the edge arriving at the run's first vertex

void load_rest(uint b) {
  R_turns = 0u;
  R_len_in = 0.0;
  uint v0 = vtx(0u);
  if (v0 >= 1u && v0 < N) R_len_in = rest_info[b + (v0 - 1u) * TVK_BLOCK].x;
  [[unroll]] for (uint k = 0u; k < RUN; ++k) {
    uint v = vtx(k);
    R_len[k] = 0.0;
    R_edge[k] = vec3(0.0);
    if (v < N) {
      vec4 info = rest_info[b + v * TVK_BLOCK];
      if (v + 1u < N) R_len[k] = info.x;
      if (info.z != 0.0) R_turns |= 1u << k;
      if (TVK_HAS(TVK_FEATURE_LOCAL_SHAPE)) R_edge[k] = rest_edge_local[b + v * TVK_BLOCK].xyz;
    }
  }
}
float len_in(uint k) { return k == 0u ? R_len_in : R_len[k - 1u]; }

// The guide's root frame now (current_root_frame, with vertices 0 and 1 from lane 0). Every lane calls it.
vec4 runs_root_frame(uint g, uint b) {
  vec3 x0 = from_lane(R_pos[0], 0u).xyz;
  vec3 x1 = from_lane(R_pos[1], 0u).xyz;
  vec4 f = quat_mul(skin_rotation(g), root_frame[g]);
  if (rest_info[b + TVK_BLOCK].z != 0.0) f = frame_align(f, x1 - x0, rest_info[b].x);
  return f;
}

// Local shape's step: local_shape_step's arithmetic, with the walk's state passed in.
void local_shape_run_step(bool turns, float rest_in, vec3 edge, float s, inout vec4 f, vec3 a, inout vec4 p,
                          inout vec4 n) {
  if (turns) f = frame_align(f, p.xyz - a, rest_in);
  precise vec3 target = p.xyz + quat_rotate(f, edge);  // precise: see integrate.glsl
  precise vec3 d = s * (target - n.xyz);
  if (p.w > 0.0) p = vec4(p.xyz - d, p.w);
  if (n.w > 0.0) n = vec4(n.xyz + d, n.w);
}

// Local shape steps a run's vertices in a loop that is not unrolled: each step reads the run's vertex at index 0 and
// its neighbours at 1 and RUN - 1, then the run turns by one place (register moves); RUN turns restore it. Unrolled,
// with the run indexed by the loop's constants, its loop measured as if it missed the instruction cache (NVIDIA H100,
// Ratboy at 240 Hz, runs of 4: 212 us, 59 of them without local shape; turning: 136 us). The sweep's step is small:
// unrolled it measured faster than turning (Ratboy 136.5 -> 129.8 us, curly 1 M in runs of 8 690 -> 608 us at 240 Hz),
// and so did reading local shape's rest data from memory instead of turning it in registers on 1 M at 240 Hz only
// (608 -> 556 us; Ratboy 130 -> 139, 1 M at 60 Hz 224 -> 228): not kept; on later kernels it lost everywhere
// (docs/simulation.md, "The run kernel").
void turn_run_shape() {
  vec4 p0 = R_pos[0];
  vec3 e0 = R_edge[0];
  float l0 = R_len[0];
  [[unroll]] for (uint j = 0u; j + 1u < RUN; ++j) {
    R_pos[j] = R_pos[j + 1u];
    R_edge[j] = R_edge[j + 1u];
    R_len[j] = R_len[j + 1u];
  }
  R_pos[RUN - 1u] = p0;
  R_edge[RUN - 1u] = e0;
  R_len[RUN - 1u] = l0;
  R_turns = (R_turns >> 1u) | ((R_turns & 1u) << (RUN - 1u));
}

// Local shape (local_shape_strand). Round t: lane t takes the first walk of the pair over its run, lane t - 1 the
// second. A walk's state at a run's start (the frame, the run's first vertex as moved, the vertex before it final) is
// the lane before's at the round's start; the last step of a run reads the next run's first vertex from its lane
// at that step, after the first walk's lane has finished it (for the second walk) or before anything touched it (for
// the first). Every lane turns its run in step, so index 1 holds each lane's first vertex at the last step.
void runs_local_shape(uint g, GroupParams gp) {
  float s = gp.local_stiffness;
  vec4 root = quat_mul(skin_rotation(g), root_frame[g]);
  vec4 cf = vec4(0, 0, 0, 1);  // the walk's frame after this lane's last step
  vec4 cp = vec4(0.0);         // the vertex after this lane's last step, as that step moved it
  for (uint it = 0u; it < gp.local_iterations; it += 2u) {
    bool pair = it + 2u <= gp.local_iterations;
    uint rounds = RL + (pair ? 1u : 0u);
    for (uint t = 0u; t < rounds; ++t) {
      vec4 lf = from_before(cf);
      vec4 lp = from_before(cp);
      vec3 la = from_before(R_pos[RUN - 1u]).xyz;
      bool mine = tvk_r == t || (pair && tvk_r + 1u == t);
      vec4 f = lf;
      vec4 carry = lp;
      [[dont_unroll]] for (uint k = 0u; k < RUN; ++k) {
        uint v = vtx(k);
        vec4 right = vec4(0.0);
        if (k + 1u == RUN) right = from_after(R_pos[1]);
        if (mine && v >= 1u && v < N) {
          vec4 p = v == 1u ? R_pos[0] : (k == 0u ? lp : carry);
          if (v + 1u < N) {
            if (v == 1u) f = root;
            vec3 a = k == 0u ? la : R_pos[RUN - 1u].xyz;
            vec4 n = k + 1u < RUN ? R_pos[1] : right;
            local_shape_run_step((R_turns & 1u) != 0u, k == 0u ? R_len_in : R_len[RUN - 1u], R_edge[0], s, f, a, p,
                                 n);
            carry = n;
          }
          R_pos[0] = p;
        }
        turn_run_shape();
      }
      if (mine) {
        cf = f;
        cp = carry;
      }
    }
  }
}

void runs_length(uint g, uint b, GroupParams gp, bool write_tangents) {
  if (TVK_HAS(TVK_FEATURE_WIND)) {
    // wind_begin / wind_step, in rounds: each vertex pushed against the one before it as pushed.
    float a = float(g % 20u) / 20.0;
    vec3 w = a * (step_params[TVK_STEP].wind[0].xyz + step_params[TVK_STEP].wind[2].xyz) +
             (1.0 - a) * (step_params[TVK_STEP].wind[1].xyz + step_params[TVK_STEP].wind[3].xyz);
    for (uint t = 0u; t < RL; ++t) {
      vec3 lb = from_before(R_pos[RUN - 1u]).xyz;
      [[unroll]] for (uint k = 0u; k < RUN; ++k) {
        uint v = vtx(k);
        if (tvk_r == t && v >= 1u && v < N && R_pos[k].w > 0.0) {
          vec3 before = k == 0u ? lb : R_pos[k - 1u].xyz;
          vec3 e = R_pos[k].xyz - before;
          float len = length(e);
          vec3 push = w;
          if (len > kDirectionEps * len_in(k)) {
            vec3 u = e / len;
            push = w - dot(w, u) * u;
          }
          R_pos[k] = vec4(R_pos[k].xyz + push, R_pos[k].w);
        }
      }
    }
  }

  if (TVK_HAS(TVK_FEATURE_COLLISION)) {
    [[unroll]] for (uint k = 0u; k < RUN; ++k) {
      tvk_k = k;
      if (vtx(k) < N) collide_vertex(g, b, vtx(k));
    }
  }

  // The sweeps (length_strand's), in rounds; the next run's first vertex and its history are read before the sweep
  // (nothing moves them before their lane's round).
  for (uint it = 0u; it < gp.length_iterations; ++it) {
    bool last_sweep = it + 1u == gp.length_iterations;
    vec4 n_right = from_after(R_pos[0]);
    vec3 pn_right = from_after(R_prev[0]).xyz;
    vec4 cp = vec4(0.0);
    for (uint t = 0u; t < RL; ++t) {
      vec4 lp = from_before(cp);
      if (tvk_r == t) {
        SweepWalk sw;
        sw.p = lp;
        [[unroll]] for (uint k = 0u; k < RUN; ++k) {
          uint v = vtx(k);
          tvk_k = k;
          if (v < N) {
            vec4 p = v == 0u ? R_pos[0] : sw.p;
            if (v + 1u < N) {
              sw = SweepWalk(p, R_prev[k].xyz, last_sweep);
              vec4 n = k + 1u < RUN ? R_pos[k + 1u] : n_right;
              vec3 pn = k + 1u < RUN ? R_prev[k + 1u].xyz : pn_right;
              R_pos[k] = sweep_step(sw, b, v, n, pn, R_len[k]);
            } else {
              R_pos[k] = p;
            }
          }
        }
        cp = sw.p;
      }
    }
  }

  // The finish (length.glsl's FinishWalk and length_reset_if_not_finite): the velocity clamp, the non-finite test of
  // the whole strand and its reset, and on the frame's last substep the tangents.
  bool ok = true;
  [[unroll]] for (uint k = 0u; k < RUN; ++k) {
    if (vtx(k) < N) {
      vec3 q = R_prev[k].xyz;
      if (TVK_HAS(TVK_FEATURE_MAX_SPEED) && gp.max_step > 0.0 && R_pos[k].w > 0.0) {
        vec3 step = R_pos[k].xyz - q;
        float len = length(step);
        if (len > gp.max_step) {
          q = R_pos[k].xyz - step * (gp.max_step / len);
          R_prev[k] = vec4(q, R_pos[k].w);
        }
      }
      ok = ok && finite3(R_pos[k].xyz) && finite3(q);
    }
  }
  if (runs_min(ok ? 1.0 : 0.0) < 0.5) {
    vec3 q0 = from_lane(R_prev[0], 0u).xyz;
    vec4 back = reset_back(g);
    bool rigid = strand_rigid(g, gp);
    [[unroll]] for (uint k = 0u; k < RUN; ++k) {
      tvk_k = k;
      if (vtx(k) < N) reset_vertex(g, b, vtx(k), q0, back, rigid);
    }
    if (tvk_r == 0u) atomicAdd(counters[pc.counter_index], 1u);
  }

  if (write_tangents) {
    // Along the edge leaving v (arriving for the tip); an edge too short to have a direction takes the tangent of the
    // nearest vertex before it that has one, the root the current root frame's +X (a walk in rounds, as the finish).
    vec4 root_now = runs_root_frame(g, b);
    float min_len = kDirectionEps * strand_rest_length(g) / float(N - 1u);
    vec3 right = from_after(R_pos[0]).xyz;
    vec3 left = from_before(R_pos[RUN - 1u]).xyz;
    vec4 last = vec4(quat_rotate(root_now, vec3(1, 0, 0)), 0.0);
    for (uint t = 0u; t < RL; ++t) {
      vec4 carried = from_before(last);
      if (tvk_r == t) {
        if (t > 0u) last = carried;
        [[unroll]] for (uint k = 0u; k < RUN; ++k) {
          uint v = vtx(k);
          if (v < N) {
            vec3 e = v + 1u < N ? (k + 1u < RUN ? R_pos[k + 1u].xyz : right) - R_pos[k].xyz
                                : R_pos[k].xyz - (k == 0u ? left : R_pos[k - 1u].xyz);
            float len = length(e);
            if (len > min_len) last = vec4(e / len, 0.0);
            tangent[b + v * TVK_BLOCK] = last;
          }
        }
      }
    }
  }
}

void main() {
  // Strands are clusters of RL invocations of a subgroup; the host makes WORKGROUP_SIZE a multiple of the subgroup
  // size and the subgroup size a multiple of RL (see frame_lanes.glsl on full subgroups).
  tvk_r = gl_SubgroupInvocationID & (RL - 1u);
  tvk_lane_base = gl_SubgroupInvocationID - tvk_r;
  uint g = gl_WorkGroupID.x * (WORKGROUP_SIZE / RL) + (gl_SubgroupID * gl_SubgroupSize + tvk_lane_base) / RL;
  if (g >= pc.guide_count || pc.step_count == 0u) return;  // uniform over the strand's lanes
  float quiet = frame_still() ? anchor[g].w : 0.0;  // a moving frame reads nothing more
  if (guide_asleep(quiet)) return;  // uniform over the strand's lanes, as padding
  if (tvk_r == 0u) note_awake();
  uint b = strand_base(g);
  R_anchor = vec4(0.0);
  [[unroll]] for (uint k = 0u; k < RUN; ++k) {
    uint v = vtx(k);
    R_pos[k] = vec4(0.0);
    R_prev[k] = vec4(0.0);
    R_prevprev[k] = vec4(0.0);
    if (v < N) {
      R_pos[k] = pos[b + v * TVK_BLOCK];
      R_prev[k] = prev[b + v * TVK_BLOCK];
    }
  }
  load_rest(b);
  GroupParams gp = guide_params(g);
  for (uint s = 0u; s < pc.step_count; ++s) {
    tvk_step = pc.step_index + s;
    tvk_skin_base = pc.skin_base + s * pc.skin_stride;
    IntegrateStrand is = integrate_strand(g);
    [[unroll]] for (uint k = 0u; k < RUN; ++k) {
      tvk_k = k;
      uint v = vtx(k);
      if (v < N) integrate_vertex_of(is, b + v * TVK_BLOCK, g, v);
    }
    if (TVK_HAS(TVK_FEATURE_COLLISION)) R_anchor = from_lane(R_anchor, 0u);
    if (TVK_HAS(TVK_FEATURE_VSP)) {
      vec4 x0 = from_lane(R_pos[0], 0u), x1 = from_lane(R_pos[1], 0u);
      vec3 y0 = from_lane(R_prev[0], 0u).xyz, y1 = from_lane(R_prev[1], 0u).xyz;
      vec3 z0 = from_lane(R_prevprev[0], 0u).xyz, z1 = from_lane(R_prevprev[1], 0u).xyz;
      VspStrand vs = vsp_strand_from(g, x0, x1, y0, y1, z0, z1);
      [[unroll]] for (uint k = 0u; k < RUN; ++k) {
        tvk_k = k;
        uint v = vtx(k);
        if (v >= 1u && v < N && R_pos[k].w > 0.0) vsp_vertex_of(vs, b + v * TVK_BLOCK, v);
      }
    }
    if (TVK_HAS(TVK_FEATURE_LOCAL_SHAPE)) runs_local_shape(g, gp);
    runs_length(g, b, gp, s + 1u == pc.step_count);
  }
  float moved2 = 0.0;
  [[unroll]] for (uint k = 0u; k < RUN; ++k) {
    uint v = vtx(k);
    if (v < N) {
      if (frame_measures()) moved2 = max(moved2, frame_move2(R_pos[k], b + v * TVK_BLOCK));
      pos[b + v * TVK_BLOCK] = R_pos[k];
      prev[b + v * TVK_BLOCK] = R_prev[k];
      if (TVK_HAS(TVK_FEATURE_VSP)) prevprev[b + v * TVK_BLOCK] = R_prevprev[k];
    }
  }
  moved2 = -runs_min(-moved2);
  if (tvk_r == 0u) anchor[g] = vec4(R_anchor.xyz, quiet_frames_after(quiet, moved2));

  if (K > 0u) {
    vec4 root_now = runs_root_frame(g, b);
    float tip_separation = gp.tip_separation;
    uint G = pc.guide_count;
    uint layers = follow_layers(G, g);
    for (uint f = 0u; f < layers; ++f) {
      vec3 offset = quat_rotate(root_now, follow_offset[g * K + f].xyz);  // follow_root_offset, lane 0's root frame
      [[unroll]] for (uint k = 0u; k < RUN; ++k) {
        uint v = vtx(k);
        if (v < N) {
          uint dst = vertex_index(follow_strand(G, g, f), v);
          pos[dst] = follow_vertex(R_pos[k], offset, tip_separation, v);
        }
      }
    }
  }
}
