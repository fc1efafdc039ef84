// The one-thread frame kernel for grooms without follow hairs (frame_private.glsl). Its module holds no follow code:
// the driver's register allocation for it depends on what the module holds (docs/simulation.md).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sim/frame_private.glsl"
