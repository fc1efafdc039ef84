// The fused frame kernel: one dispatch per frame runs every substep and every pass the scene needs for a block of
// strands, one thread per guide (strands never interact), with the strand's state held on chip the whole frame. The
// state is read once and written once per frame; tangents are written after the last substep only; prevprev (VSP's
// second history) is never read (integration overwrites it before anything reads it) and written only when VSP runs;
// follow hairs are written at the end by their guide's thread. The pass math is the same functions the pass-per-
// dispatch shaders call (integrate.glsl, vsp.glsl, local_shape.glsl, length.glsl, follow.glsl), run in the same
// order, so both paths give the same float results.
//
// The includer (frame.comp: private arrays; frame_shared.comp: shared memory) first defines the on-chip storage:
// TVK_POS/TVK_PREV/TVK_PREVPREV(i) for element i of the blocked layout, and frame_storage_begin(g).
// Specialisation: FEATURES carries TVK_FEATURE_VSP and TVK_FEATURE_LOCAL_SHAPE on top of the per-pass bits, so a
// scene without VSP, local shape, wind, collision, clamp or skinning compiles none of their code.
#ifndef TRESSVK_SIM_FRAME_GLSL
#define TRESSVK_SIM_FRAME_GLSL

#define TVK_FRAME_KERNEL 1
#ifdef TVK_FOLLOWS
uint tvk_follow_layers;  // follow_layers of the thread's guide: the follows written
#endif
vec4 tvk_anchor_now;  // this substep's anchor of the thread's guide (integrate writes it, collision reads it)
uint tvk_step;        // this substep's index into step_params
uint tvk_skin_base;   // this substep's first vec4 of skinning data
#define TVK_ANCHOR(g) tvk_anchor_now
#define TVK_STEP tvk_step
#define TVK_SKIN_BASE tvk_skin_base

#include "sim/integrate.glsl"
#include "sim/vsp.glsl"
#include "sim/local_shape.glsl"
#include "sim/length.glsl"
#include "sim/follow.glsl"

void run_substep(uint g, uint b, uint s, bool last) {
  tvk_step = pc.step_index + s;
  tvk_skin_base = pc.skin_base + s * pc.skin_stride;
  IntegrateStrand is = integrate_strand(g);
  // Integration and VSP vertex by vertex, with what they read of the guide and the substep read once (is, vs): VSP
  // of vertex v reads the pinned root vertices (integrated first, vertices 0 and 1) and vertex v's own state, so the
  // order gives the passes' results while each vertex's second history lives only from its integration to its VSP
  // (frame.comp keeps it in registers). The last substep stores that history (the state's prevprev) at once.
  integrate_vertex_of(is, b, g, 0u);
  integrate_vertex_of(is, b + TVK_BLOCK, g, 1u);
  VspStrand vs;
  if (TVK_HAS(TVK_FEATURE_VSP)) vs = vsp_strand(g);
  for (uint v = 0u; v < N; ++v) {
    uint i = b + v * TVK_BLOCK;
    if (v >= 2u) integrate_vertex_of(is, i, g, v);
    if (TVK_HAS(TVK_FEATURE_VSP)) {
      vsp_vertex_of(vs, i, v);
      if (last) prevprev[i] = TVK_PREVPREV(i);
    }
  }
  if (TVK_HAS(TVK_FEATURE_LOCAL_SHAPE)) local_shape_strand(g);
  length_strand(g, last);
}

void main() {
  uint g = gl_GlobalInvocationID.x;
  if (g >= pc.guide_count || pc.step_count == 0u) return;
  float quiet = frame_still() ? anchor[g].w : 0.0;  // a moving frame reads nothing more
  if (guide_asleep(quiet)) return;  // one thread per guide: no barrier or subgroup operation to keep
  note_awake();
  frame_storage_begin(g);
  uint b = strand_base(g);
#ifdef TVK_FOLLOWS
  tvk_follow_layers = follow_layers(pc.guide_count, g);
#endif
  for (uint v = 0u; v < N; ++v) {
    uint i = b + v * TVK_BLOCK;
    TVK_POS(i) = pos[i];
    TVK_PREV(i) = prev[i];
  }
  // The last substep is peeled so that only it compiles the tangent writes.
  for (uint s = 0u; s + 1u < pc.step_count; ++s) run_substep(g, b, s, false);
  run_substep(g, b, pc.step_count - 1u, true);
#ifdef TVK_FOLLOWS
  // Follow hairs from the final guide (skinning data of the last substep, as the follow pass), each vertex written
  // with its guide's, their tangents with the guide's (length.glsl, write_tangent). Written in a walk of their own
  // after the guide's, reading its tangents back, they cost the kernel half its occupancy (NVIDIA H100: 255 registers
  // against 168; 64 Ratboys with 2 follows at 240 Hz 2,353 us a frame against 1,955).
  vec3 follow_offset_of[K + 1u];  // + 1: a valid size for any K
  float tip_separation = guide_params(g).tip_separation;
  for (uint f = 0u; f < K; ++f) follow_offset_of[f] = follow_root_offset(g, f);
#endif
  float moved2 = 0.0;
  for (uint v = 0u; v < N; ++v) {
    uint i = b + v * TVK_BLOCK;
    if (frame_measures()) moved2 = max(moved2, frame_move2(TVK_POS(i), i));
    pos[i] = TVK_POS(i);
    prev[i] = TVK_PREV(i);
#ifdef TVK_FOLLOWS
    for (uint f = 0u; f < K; ++f) {
      if (f >= tvk_follow_layers) break;
      uint dst = vertex_index(follow_strand(pc.guide_count, g, f), v);
      pos[dst] = follow_vertex(TVK_POS(i), follow_offset_of[f], tip_separation, v);
    }
#endif
  }
  anchor[g] = vec4(tvk_anchor_now.xyz, quiet_frames_after(quiet, moved2));
}

#endif
