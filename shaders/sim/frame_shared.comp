// The fused frame kernel (frame.glsl) with the strand block's state in workgroup shared memory, in the blocked
// layout of the buffers (lane-contiguous: no bank conflicts): one thread per guide, 32 threads = one strand block.
// The host uses it only where 32 x N x 16 bytes x 2 fit the device's shared memory.
#version 450
#extension GL_GOOGLE_include_directive : require
#define TVK_FOLLOWS 1  // any K: this variant is one module
#include "sim/layout.glsl"
layout(local_size_x = 32) in;

shared vec4 s_pos[TVK_BLOCK * N];
shared vec4 s_prev[TVK_BLOCK * N];
// VSP's second history lives from a vertex's integration to its VSP only (frame.glsl): registers, one slot per root
// vertex (vsp_strand reads both) and one for the vertex being integrated.
vec4 s_prevprev[3];
uint tvk_frame_base;  // the workgroup's first element: each thread touches only its own strand's elements
#define TVK_POS(i) s_pos[(i) - tvk_frame_base]
#define TVK_PREV(i) s_prev[(i) - tvk_frame_base]
#define TVK_PREVPREV(i) s_prevprev[min(((i) - tvk_frame_base) / TVK_BLOCK, 2u)]
void frame_storage_begin(uint g) { tvk_frame_base = gl_WorkGroupID.x * (TVK_BLOCK * N); }

#include "sim/frame.glsl"
