#version 460
#extension GL_GOOGLE_include_directive : require
// Hair shading with the shadow map (binding 4).
#define TVK_SHADOWED 1
#include "render/hair_shade.glsl"
