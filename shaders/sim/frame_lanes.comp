// The compliant model's lane-parallel frame kernel, one strand per workgroup, lanes exchanging values through shared
// memory (any subgroup size; N up to 128). The kernel: frame_lanes.glsl, lanes_compliant.glsl.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sim/frame_lanes.glsl"
