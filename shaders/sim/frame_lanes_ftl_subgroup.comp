// The follow-the-leader model's lane-parallel frame kernel, each strand a cluster of lanes of one subgroup exchanging
// values by shuffles (where the subgroup holds the power of two >= N lanes). The kernel: frame_lanes.glsl,
// lanes_ftl.glsl.
#version 450
#extension GL_GOOGLE_include_directive : require
#define TVK_LANES_FTL 1
#define TVK_LANES_SUBGROUP 1
#include "sim/frame_lanes.glsl"
