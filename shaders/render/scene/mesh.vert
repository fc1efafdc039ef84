#version 460
#extension GL_GOOGLE_include_directive : require
// Scene meshes: world position and normal for lighting.
#include "render/scene/scene_layout.glsl"

layout(location = 0) out vec3 o_world;
layout(location = 1) out vec3 o_normal;
layout(location = 2) out float o_paint;

void main() {
  const vec4 p = pc.model * vec4(vertex_data[2 * gl_VertexIndex].xyz, 1.0);
  o_world = p.xyz;
  const vec4 n = vertex_data[2 * gl_VertexIndex + 1];
  o_normal = mat3(pc.model) * n.xyz;  // rigid transforms only
  o_paint = n.w;                      // 0..1: painted with the hair-root colour (the sample head's scalp)
  gl_Position = scene.view_proj * p;
}
