// The one-thread frame kernel (frame.glsl) with the strand's state in private arrays (registers, or the GPU's
// per-thread local memory when they do not fit): one thread per guide, in workgroups of 32 or 512 threads (sim/fused.hpp).
// frame.comp compiles it for grooms without follow hairs, frame_follows.comp with them (TVK_FOLLOWS).
#ifndef TRESSVK_SIM_FRAME_PRIVATE_GLSL
#define TRESSVK_SIM_FRAME_PRIVATE_GLSL
#include "sim/layout.glsl"
layout(local_size_x_id = 0) in;  // WORKGROUP_SIZE: a multiple of 32 strands (sim/fused.cpp, frame_private_workgroup)

vec4 s_pos[N];
vec4 s_prev[N];
// VSP's second history lives from a vertex's integration to its VSP only (frame.glsl): one slot per root vertex
// (vsp_strand reads both) and one for the vertex being integrated.
vec4 s_prevprev[3];
uint tvk_frame_base;  // strand_base of the thread's guide: element i is vertex (i - base) / TVK_BLOCK
#define TVK_POS(i) s_pos[((i) - tvk_frame_base) / TVK_BLOCK]
#define TVK_PREV(i) s_prev[((i) - tvk_frame_base) / TVK_BLOCK]
#define TVK_PREVPREV(i) s_prevprev[min(((i) - tvk_frame_base) / TVK_BLOCK, 2u)]
void frame_storage_begin(uint g) { tvk_frame_base = strand_base(g); }

#include "sim/frame.glsl"

#endif
