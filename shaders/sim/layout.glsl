// GPU data layout of the TressVK simulation: every simulation shader includes this file.
// Mirrored on the host by plugin/model/include/tressvk/model/gpu_layout.hpp; the two must change together (the host side has
// static_asserts on every size and offset written here).
//
// One descriptor set (set 0) per hair instance, storage buffers only. Sizes: G guides, K follows per guide,
// N vertices per strand. Strands are numbered in the asset's order: guides 0..G-1, then follow f of guide g is
// strand (f+1)*G+g. Per-vertex buffers hold strands in blocks of TVK_BLOCK, vertex-major within a block, so that
// the threads of a subgroup walking their strands (local shape, length) read consecutive addresses: vertex v of
// strand s is at strand_base(s) + v * TVK_BLOCK (see vertex_index). Buffers hold whole blocks; threads of the padding
// strands return at once.
//
// Simulation space: world-oriented axes (gravity and wind are world vectors), origin at the instance translation
// plus the rotated asset origin, which the host keeps in double precision. Within it every guide has an anchor, its
// skinned rest root at the current step (anchor[g], written by integrate), and the state (pos, prev, prevprev) holds
// offsets from the anchor of its guide (a follow uses its guide's anchor): a vertex is at anchor[g] + pos[i]. So
// float32 holds strand-sized numbers only, wherever the strand is on the character and wherever the character is:
// rounding is relative to the strand, not to the head (a 1 mm segment 0.4 m from the asset origin would otherwise
// carry 3e-8 m of rounding per coordinate, a 2e-5 rad direction error, which the strand's lever arm multiplies).
// Each step the state is re-expressed against the new anchor by the anchor's move, which the host computes in
// double (skin rows [6..8]), so the move adds no rounding that differs along the strand.
#ifndef TRESSVK_SIM_LAYOUT_GLSL
#define TRESSVK_SIM_LAYOUT_GLSL

// Binding numbers, constant ids, feature bits, TVK_BLOCK, TVK_SKIN_VEC4, TVK_STEP_*: one definition for GLSL and C++.
#include "tressvk/model/gpu_layout.h"
#if TVK_SPEC_WORKGROUP_SIZE != 0 || TVK_SPEC_VERTICES_PER_STRAND != 1 || TVK_SPEC_FOLLOW_PER_GUIDE != 2 || \
    TVK_SPEC_FEATURES != 3 || TVK_SPEC_CAPSULE_COUNT != 4 || TVK_BINDING_POSITIONS != 0 || \
    TVK_BINDING_PREV_POSITIONS != 1 || TVK_BINDING_PREV_PREV_POSITIONS != 2 || TVK_BINDING_TANGENTS != 3 || \
    TVK_BINDING_REST_POSITIONS != 4 || TVK_BINDING_REST_INFO != 5 || TVK_BINDING_REST_EDGE_LOCAL != 6 || \
    TVK_BINDING_ROOT_FRAMES != 7 || TVK_BINDING_FOLLOW_OFFSETS != 8 || TVK_BINDING_GUIDE_INFO != 9 || \
    TVK_BINDING_BONE_INDICES != 10 || TVK_BINDING_BONE_WEIGHTS != 11 || TVK_BINDING_SKIN != 12 || \
    TVK_BINDING_GROUPS != 13 || TVK_BINDING_STEPS != 14 || TVK_BINDING_COUNTERS != 15 || TVK_BINDING_ANCHORS != 16
#error "layout.glsl's constant ids or bindings differ from tressvk/model/gpu_layout.h"
#endif

// ---- specialization constants (one pipeline per combination that a scene uses) -------------------------
layout(constant_id = 0) const uint WORKGROUP_SIZE = 64;   // used with local_size_x_id = 0; any size works
layout(constant_id = 1) const uint N = 32;                // vertices per strand (4..128)
layout(constant_id = 2) const uint K = 0;                 // follow hairs per guide
layout(constant_id = 3) const uint FEATURES = 0;          // TVK_FEATURE_* bits (gpu_layout.h)
layout(constant_id = 4) const uint CAPSULE_COUNT = 0;     // 0..8, capsules tested by the length pass

#define TVK_HAS(bit) ((FEATURES & (bit)) != 0u)

// ---- vertex layout (TVK_BLOCK and TVK_VERTEX_INDEX in gpu_layout.h; TVK_STRAND_BLOCK in tressvk.h) ---
uint strand_base(uint s) { return (s / TVK_BLOCK) * (TVK_BLOCK * N) + s % TVK_BLOCK; }
uint vertex_index(uint s, uint v) { return strand_base(s) + v * TVK_BLOCK; }
// The strand of follow f of guide g, of G guides.
uint follow_strand(uint G, uint g, uint f) { return G + f * G + g; }
// The strand and vertex of element i of a per-vertex buffer (for one-thread-per-vertex passes, thread i = element i).
uvec2 element_strand_vertex(uint i) {
  uint block = i / (TVK_BLOCK * N);
  uint r = i - block * (TVK_BLOCK * N);
  return uvec2(block * TVK_BLOCK + r % TVK_BLOCK, r / TVK_BLOCK);
}

// ---- per-instance dynamic state --------------------------------------------------------------------------
layout(std430, set = 0, binding = 0) buffer Positions { vec4 pos[]; };        // padded(G*(K+1))*N; w = inverse mass (0 = pinned)
layout(std430, set = 0, binding = 1) buffer PrevPositions { vec4 prev[]; };   // padded(G)*N, previous step
layout(std430, set = 0, binding = 2) buffer PrevPrevPositions { vec4 prevprev[]; };  // padded(G)*N, two steps back (VSP)
layout(std430, set = 0, binding = 3) buffer Tangents { vec4 tangent[]; };     // padded(G)*N: the guides' (a follow's is its guide's); xyz unit, w = 0

// ---- per-asset static data (shared by every instance of an asset; built by model::build_gpu_static) ---
// v = 0: the root in asset space (relative to the asset origin); v > 0: the offset from the root. w = inverse mass.
layout(std430, set = 0, binding = 4) readonly buffer RestPositions { vec4 rest_pos[]; };  // padded(G)*N
// x: rest length of edge v->v+1 (0 for v = N-1); y: rest arc length of v from the root / strand rest length;
// z: 1 when the local-shape frame turns onto the edge arriving at v, 0 when that edge is too short to have a
//    reliable direction (the frame is carried over it); w: 0.
layout(std430, set = 0, binding = 5) readonly buffer RestInfo { vec4 rest_info[]; };      // padded(G)*N
layout(std430, set = 0, binding = 6) readonly buffer RestEdgeLocal { vec4 rest_edge_local[]; };  // padded(G)*N: edge leaving v in the model frame at v; w = 0
layout(std430, set = 0, binding = 7) readonly buffer RootFrames { vec4 root_frame[]; };   // G: rest frame at the root, quaternion (x,y,z,w)
layout(std430, set = 0, binding = 8) readonly buffer FollowOffsets { vec4 follow_offset[]; };  // G*K, in the root frame; w = 0
// x: strand group; y: 0 (reserved flags); z: floatBitsToUint(strand rest length, m); w: 0.
layout(std430, set = 0, binding = 9) readonly buffer GuideInfo { uvec4 guide_info[]; };   // G
layout(std430, set = 0, binding = 10) readonly buffer BoneIndices { uvec4 bone_index[]; }; // G (read only with SKINNING)
layout(std430, set = 0, binding = 11) readonly buffer BoneWeights { vec4 bone_weight[]; }; // G (read only with SKINNING)

// ---- per-frame parameters, written by the host into a ring (one slice per frame in flight) ----------------
// Skinning, per substep s and bone b, TVK_SKIN_VEC4 vec4 at skin[pc.skin_base + TVK_SKIN_VEC4*b] (pc.skin_base
// selects the substep): [0..2] rows of the affine 3x4 map from asset space (rest positions) to simulation space,
// instance motion included; [3] the rotation of that map as a quaternion (x,y,z,w); [4] its rotation since the
// previous step (identity at a reset), computed in double on the host: the rigid motion VSP propagates; [5] the
// previous step's [4], in this step's frame (turned with a teleport or carry; identity after a reset); [6..8] rows of
// the map's change since the previous step (this map minus the previous one carried into this step's frame; zero at
// a reset): applied to a rest root, the move of that guide's anchor.
layout(std430, set = 0, binding = 12) readonly buffer Skin { vec4 skin[]; };

struct GroupParams {            // per strand group; std430, 64 bytes. Everything already per step (h folded in).
  float velocity_keep;          // exp(-damping * h * 60)
  float global_stiffness;       // 0..1 per step (0 when the GLOBAL_SHAPE feature is off for this group)
  float global_range;           // arc-length fraction of the strand from the root
  float local_stiffness;        // 0.5 * min(local_stiffness, 0.95): the per-iteration fraction
  uint local_iterations;        // honoured for every N
  uint length_iterations;
  float vsp_coefficient;        // 0..1
  float vsp_threshold;          // m per step^2: a * h^2
  float max_step;               // m per step: max_speed * h (used with MAX_SPEED)
  float tip_separation;         // resolved (the asset's baked value when the params said "asset")
  float reserved0;
  float reserved1;
  float rigid_below;            // m: strands shorter than this are carried rigidly, every vertex pinned (0 = none)
  float reserved2;
  float reserved3;
  float reserved4;
};
layout(std430, set = 0, binding = 13) readonly buffer Groups { GroupParams group[]; };

struct StepParams {             // per substep; std430, 640 bytes. Everything in simulation space, per step.
  vec4 gravity;                 // xyz: g * h^2 (m); w: h (s)
  vec4 origin_shift;            // xyz: move of the simulation origin since the last step (in the anchors' move already)
  vec4 teleport;                // quaternion (x,y,z,w) turning the state about the origin (identity when none)
  uvec4 flags;                  // x: TVK_STEP_* bits; y: substep index within the frame; z, w: 0
  vec4 wind[4];                 // xyz: wind acceleration * h^2 (m), the pyramid blended per strand; w: 0
  vec4 capsule[16];             // capsule c: [2c] = (p0, r0), [2c+1] = (p1, r1)
  vec4 capsule_move[16];        // capsule c: [2c].xyz = move of p0 since the last step, [2c+1].xyz = of p1
};
layout(std430, set = 0, binding = 14) readonly buffer Steps { StepParams step_params[]; };

// Words the host reads back (host-visible), one per frame slot, [pc.counter_index]: bits 0-30 count the strands reset
// after going non-finite in the slot's frames (the host sums the slots), bit 31 is the slot's awake bit (below,
// "Sleeping strands"). (One word at the push constant's index, not a reset count at a constant index and an awake
// word beside it: with either of those the driver compiles the one-thread kernel to 230 registers instead of 128, and
// 4 M guide vertices at 240 Hz take 2,334 us instead of 1,775 on an H100.)
layout(std430, set = 0, binding = 15) buffer Counters { uint counters[]; };
const uint kAwakeBit = TVK_COUNTER_AWAKE_BIT;

// Per guide: xyz its anchor in simulation space (the skinned rest root at the current step), w = 0.
layout(std430, set = 0, binding = 16) buffer Anchors { vec4 anchor[]; };

layout(push_constant) uniform PushConstants {   // 36 bytes
  uint guide_count;     // G: dispatches cover exactly G guides' work, every thread bounds-checks
  uint step_index;      // index into step_params
  uint skin_base;       // first vec4 of this substep's skinning data in skin[]
  uint group_base;      // index of this instance's group 0 in group[]
  uint counter_index;   // this frame slot's word in counters[]
  uint step_count;      // fused frame kernel: substeps to run (step_index .. step_index + step_count - 1)
  uint skin_stride;     // fused frame kernel: vec4 of skinning data per substep
  float rest_move;      // fused frame kernels: in a still frame, the sleeping threshold (m per step, below); else 0
  uint follow_strands;  // rendered strands whose follow hairs are written (a prefix: guides, then follow layers)
} pc;
// The follow layers of guide g among the strands the host draws this frame (tressvk_set_draw_strands): follow f is
// written iff f < follow_layers (its strand G + f G + g below pc.follow_strands); the renderer draws no more strands
// than the last frame that ran wrote. Once per guide, so that a groom drawn whole pays a compare per follow only.
uint follow_layers(uint G, uint g) {
  uint first = G + g;  // layer 0's strand of guide g
  return pc.follow_strands > first ? min(K, (pc.follow_strands - first + G - 1u) / G) : 0u;
}

// ---- sleeping strands (the fused frame kernels; the pass-per-dispatch path never sleeps) -------------------------
// A frame is still when the host finds that every input its steps see (skinning, step and group parameters) is the
// same as in the previous frame's last step: nothing but the strands' own motion can move them. In a still frame
// |pc.rest_move| is the sleeping threshold in metres per step (TvkSimSettings::sleep_below times the groom's median
// strand length, the length every error here is relative to); it is 0 in a frame that is not still. anchor[g].w
// counts the measured still frames in a row in which no vertex of guide g moved more than that per step over the
// frame; once it reaches kQuietFrames the guide sleeps: the kernels treat it as padding (no state read, nothing
// written: positions, tangents and follows keep their values) until a frame that is not still sets the count back to
// 0. The move is measured on positions across the frame (pos - prev is not the velocity: the length pass's velocity
// correction keeps it nonzero at rest), so a swing's turning point, where the velocity passes through zero but the
// vertex still accelerates, is not rest. Measuring re-reads the frame's starting positions (frame_move2), so only one
// still frame in kMeasureEvery measures (rest_move > 0; the others pass it negative and keep the count): a groom that
// never comes to rest pays a quarter of that read, and a moving frame reads nothing more at all.
// An instance whose every guide sleeps costs nothing: in a still frame every guide that runs (is not asleep as the
// frame starts) sets its frame slot's awake bit (the host clears it as it records the frame); the host reads it
// frames_in_flight frames later, and once a still frame ran no guide it records no dispatch for the instance until a
// frame is not still (simulate.cpp, "Idle instances").
const float kQuietFrames = float(TVK_QUIET_FRAMES);
bool frame_still() { return pc.rest_move != 0.0; }
bool frame_measures() { return pc.rest_move > 0.0; }
bool guide_asleep(float quiet) { return frame_still() && quiet >= kQuietFrames; }
// The squared move over the frame of the vertex at element i, whose end-of-frame position is p (before it is stored).
float frame_move2(vec4 p, uint i) {
  vec3 d = p.xyz - pos[i].xyz;
  return dot(d, d);
}
// The count after this frame, from the count before it and the largest squared move of the strand's vertices.
float quiet_frames_after(float quiet, float moved2) {
  if (!frame_measures()) return frame_still() ? quiet : 0.0;
  float limit = pc.rest_move * float(pc.step_count);
  return moved2 <= limit * limit ? min(quiet + 1.0, kQuietFrames) : 0.0;
}
// Called by one invocation of each guide that runs in this frame.
void note_awake() {
  if (frame_still()) atomicOr(counters[pc.counter_index], kAwakeBit);
}

#endif
