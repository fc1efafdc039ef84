#version 460
#extension GL_GOOGLE_include_directive : require
// Hair shading with the shadow map (binding 5, TVK_DRAW_BINDING_SHADOW_MAP).
#define TVK_SHADOWED 1
#include "render/hair_shade.glsl"
