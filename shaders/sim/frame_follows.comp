// The one-thread frame kernel for grooms with follow hairs (frame_private.glsl): each follow vertex is written with
// its guide's.
#version 450
#extension GL_GOOGLE_include_directive : require
#define TVK_FOLLOWS 1
#include "sim/frame_private.glsl"
