#version 460
#extension GL_GOOGLE_include_directive : require
// Hair shading pass: camera-facing quads with what the fragment shader needs for coverage and Kajiya-Kay.
#include "render/hair_layout.glsl"
#include "render/hair_expand.glsl"

layout(location = 0) out vec3 o_position;
layout(location = 1) out vec3 o_tangent;
layout(location = 2) noperspective out float o_offset_px;
layout(location = 3) noperspective out float o_width_px;
layout(location = 4) out float o_along;
layout(location = 5) flat out uint o_group;
layout(location = 6) flat out float o_tint;

void main() {
  const Expanded e = expand_vertex(uint(gl_VertexIndex));
  o_position = e.position;
  o_tangent = e.tangent;
  o_offset_px = e.offset_px;
  o_width_px = e.width_px;
  o_along = e.along;
  o_group = e.group;
  o_tint = e.tint;
}
