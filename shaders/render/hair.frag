#version 460
#extension GL_GOOGLE_include_directive : require
// Hair shading without a shadow map.
#include "render/hair_shade.glsl"
