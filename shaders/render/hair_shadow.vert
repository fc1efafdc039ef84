#version 460
#extension GL_GOOGLE_include_directive : require
// Hair into the host's shadow map: light-facing quads at least one texel wide, depth only (no fragment shader).
#include "render/hair_layout.glsl"
#include "render/hair_expand.glsl"

void main() { expand_vertex(uint(gl_VertexIndex)); }
