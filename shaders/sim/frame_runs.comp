// The follow-the-leader model's run kernel: each lane holds a run of 8 consecutive vertices of a strand, a strand is a
// cluster of lanes of one subgroup. The kernel: frame_runs.glsl.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sim/frame_runs.glsl"
