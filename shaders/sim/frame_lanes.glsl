// The lane-parallel frame kernel of the compliant model (the reference's SimModel::kCompliant, docs/accuracy.md): one
// dispatch per frame runs every substep, one lane per vertex. Each lane keeps its vertex's state (position, history,
// VSP's second history) and its rest data in registers for the whole frame. Integration and VSP are the per-vertex
// functions every path calls (integrate.glsl, vsp.glsl); the model's own passes, whose solves are parallel over the
// lanes (parallel cyclic reduction, reductions), are in lanes_compliant.glsl; the step's finish (velocity clamp,
// non-finite reset, tangents) and the follow hairs are here.
//
// Lanes see each other's values only through the exchange below, which has two backends:
//   frame_lanes_subgroup.comp (TVK_LANES_SUBGROUP): a strand is a cluster of LANES consecutive invocations of one subgroup
//     (LANES = the power of two >= N, so the host uses it where the subgroup holds LANES lanes: N <= 32 on NVIDIA);
//     values move by subgroup shuffles, with no shared memory and no barrier; a workgroup holds WORKGROUP_SIZE / LANES
//     strands.
//   frame_lanes.comp: one strand per workgroup of LANES = WORKGROUP_SIZE invocations (any subgroup size, N up to 128);
//     values move through shared memory between barriers.
// Both run the same arithmetic in the same order.
// An exchange is lanes_put (every lane publishes up to three values), lanes_get* (any lane's published value, called
// by every lane of the strand: shuffles need their source active), valid until the next lanes_put.
#ifdef TVK_LANES_SUBGROUP
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_shuffle : require
#extension GL_KHR_shader_subgroup_vote : require
#define TVK_EXCHANGE_LOOP
#else
// Loops whose every round is an exchange (a barrier) stay loops in the shared-memory variant: lavapipe compiles a
// workgroup's barriers as coroutine suspensions, at a cost that grows with their number, and unrolled they were
// hundreds (the conservative model's 32-vertex pipeline took 47 s to compile, 19 s with these loops kept). On an
// NVIDIA H100 the variant measured the same either way (64-vertex strands, both models).
#extension GL_EXT_control_flow_attributes : require
#define TVK_EXCHANGE_LOOP [[dont_unroll]]
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

// The conservative local shape's systems (lanes_compliant.glsl), one per strand of the workgroup (slot: the strand's
// place in it): N nodes of kNodeFloats floats; one float where the variant is not compiled or its local shape does
// not run (no group with local iterations). The driver keeps a declared array whether or not the code reaches it, and
// on an NVIDIA H100 (driver 580.159.04) a workgroup of 32 KB or more of shared memory runs alone on its SM: the
// conservative kernel without local shape took 629 us for curly 1 M guide vertices with the array, 405 without.
const uint kConservativeOn = (FEATURES >> 8u) & 1u;  // TVK_FEATURE_CONSERVATIVE
const uint kConservativeShape = TVK_HAS(TVK_FEATURE_LOCAL_SHAPE) ? kConservativeOn : 0u;
const uint kSlots = WORKGROUP_SIZE / LANES;          // strands per workgroup
const uint kNodeFloats = 37u;
// After a strand's N nodes, what its system's two halves hand each other (lanes_compliant.glsl, conservative_solve).
const uint kExchangeFloats = 33u;
// A strand's floats, odd so that the invocations solving the workgroup's systems side by side (one a strand, at the
// same node at once) read different banks of the shared memory: at N * 37 floats every one of them read the same.
const uint kSlotFloats = (N * kNodeFloats + kExchangeFloats) | 1u;
// The invocations that solve: the upper halves of the systems (first nodes) the workgroup's first kSlots, the lower
// halves kSlots from the next 32 (another NVIDIA subgroup, so that both halves run at once) where the workgroup has them.
const uint kLowerSplit = ((kSlots + 31u) / 32u) * 32u;
const uint kLowerFirst = kLowerSplit + kSlots <= WORKGROUP_SIZE ? kLowerSplit : kSlots;
shared float s_blk[1u + kConservativeShape * (kSlots * kSlotFloats - 1u)];
shared uint s_iters;
shared uint s_awake;  // still frames: whether any strand of the workgroup is awake
uint tvk_iterations = 0u;  // the most local-shape iterations of the workgroup's strands (conservative shape only)
uint tvk_slot_strand = 0u;
// False for the lanes of a strand past the last guide (the subgroup variant's last workgroup): where the conservative
// shape's barriers need every invocation of the workgroup, they run the last guide's steps and write nothing.
bool tvk_active = true;

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
#include "sim/length.glsl"  // finite3, constraint_direction, collide_vertex (not its per-strand walks)
#include "sim/follow.glsl"

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
  TVK_EXCHANGE_LOOP for (uint s = LANES / 2u; s > 0u; s >>= 1u) {
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
// The guide's root frame now (current_root_frame, with vertices 0 and 1 from their lanes). Every lane calls it.
vec4 lanes_root_frame(uint g, uint b, uint v) {
  lanes_put(v, L_pos, vec4(0.0), vec4(0.0));
  vec3 x0 = lanes_get0(0u).xyz;
  vec3 x1 = lanes_get0(1u).xyz;
  vec4 f = quat_mul(skin_rotation(g), root_frame[g]);
  if (rest_info[b + TVK_BLOCK].z != 0.0) f = frame_align(f, x1 - x0, rest_info[b].x);
  return f;
}

// The end of a step, after the model's length solve (length.glsl's FinishWalk and length_reset_if_not_finite, every
// lane at once): the velocity clamp, the non-finite test of the whole strand (a non-finite strand is reset to its
// rest pose, its history carried back by this step's rigid motion, and counted), and on the frame's last substep the
// tangents.
void finish_lanes(uint g, uint b, uint v, GroupParams gp, bool write_tangents) {
  bool vert = v < N;
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
    lanes_put(v, L_prev, vec4(0.0), vec4(0.0));
    vec3 q0 = lanes_get0(0u).xyz;
    if (vert) reset_vertex(g, b, v, q0, reset_back(g), strand_rigid(g, gp));
    if (v == 0u && tvk_active) atomicAdd(counters[pc.counter_index], 1u);
  }

  if (write_tangents) {
    vec4 root_now = lanes_root_frame(g, b, v);
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
    TVK_EXCHANGE_LOOP for (uint round = 0u; round < N; ++round) {
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
    if (vert && tvk_active) {
      if (!found) last = quat_rotate(root_now, vec3(1, 0, 0));
      tangent[b + v * TVK_BLOCK] = vec4(last, 0.0);
    }
  }
}

#include "sim/lanes_compliant.glsl"

void main() {
#ifdef TVK_LANES_SUBGROUP
  // Strands are clusters of LANES invocations of a subgroup; the host makes WORKGROUP_SIZE a multiple of the
  // subgroup size and the subgroup size a multiple of LANES, so that the subgroups are full (Vulkan would allow
  // partial ones without VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT, which needs a device feature the
  // host may not have enabled; no implementation we know launches them for such a workgroup) and this numbering
  // covers every strand of the workgroup once.
  uint v = gl_SubgroupInvocationID & (LANES - 1u);
  tvk_lane_base = gl_SubgroupInvocationID - v;
  tvk_slot_strand = (gl_SubgroupID * gl_SubgroupSize + tvk_lane_base) / LANES;
  uint g = gl_WorkGroupID.x * kSlots + tvk_slot_strand;
#else
  uint v = gl_LocalInvocationID.x;
  uint g = gl_WorkGroupID.x;
#endif
  if (pc.step_count == 0u) return;  // uniform over the dispatch
  if (g >= pc.guide_count) {        // uniform over the strand's lanes
    if (kConservativeOn == 0u) return;
    tvk_active = false;
    g = pc.guide_count - 1u;
  }
  // A sleeping guide (layout.glsl) is padding too: it returns, or where the conservative shape's barriers need it,
  // runs its steps and writes nothing (and the workgroup returns when all its strands sleep, below).
  float quiet = frame_still() ? anchor[g].w : 0.0;  // a moving frame reads nothing more
  if (tvk_active && guide_asleep(quiet)) {  // uniform over the strand's lanes
    if (kConservativeOn == 0u) return;
    tvk_active = false;
  }
  if (kConservativeOn != 0u && frame_still()) {  // uniform over the dispatch: moving frames skip these barriers
    if (gl_LocalInvocationIndex == 0u) s_awake = 0u;
    barrier();
    if (tvk_active) atomicOr(s_awake, 1u);
    barrier();
    if (s_awake == 0u) return;  // every strand of the workgroup asleep or padding: nothing read
  }
  if (v == 0u && tvk_active) note_awake();
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
  if (kConservativeOn != 0u) {
    if (gl_LocalInvocationIndex == 0u) s_iters = 0u;
    barrier();
    // The most iterations of the workgroup's active strands, plus one: 0 when every strand is padding or asleep.
    if (tvk_active) atomicMax(s_iters, gp.local_iterations + 1u);
    barrier();
    if (s_iters == 0u) return;  // uniform over the workgroup
    tvk_iterations = s_iters - 1u;
  }
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
  // Every lane of the strand reduces (the exchange's rule): frame_measures() is uniform over the dispatch.
  float moved2 = 0.0;
  if (frame_measures()) moved2 = lanes_max(v, vert ? frame_move2(L_pos, i) : 0.0);
  if (vert && tvk_active) {
    pos[i] = L_pos;
    prev[i] = L_prev;
    if (TVK_HAS(TVK_FEATURE_VSP)) prevprev[i] = L_prevprev;
  }
  if (v == 0u && tvk_active) anchor[g] = vec4(L_anchor.xyz, quiet_frames_after(quiet, moved2));

  if (K > 0u) {
    vec4 root_now = lanes_root_frame(g, b, v);
    float tip_separation = gp.tip_separation;
    uint G = pc.guide_count;
    uint layers = follow_layers(G, g);
    for (uint f = 0u; f < layers && vert && tvk_active; ++f) {
      vec3 offset = quat_rotate(root_now, follow_offset[g * K + f].xyz);  // follow_root_offset, the lanes' root frame
      uint dst = vertex_index(follow_strand(G, g, f), v);
      pos[dst] = follow_vertex(L_pos, offset, tip_separation, v);
    }
  }
}
