#version 460
#extension GL_GOOGLE_include_directive : require
// Scene meshes: world position and normal for lighting.
#include "render/scene/scene_layout.glsl"

layout(location = 0) out vec3 o_world;
layout(location = 1) out vec3 o_normal;

void main() {
  const vec4 p = pc.model * vec4(vertex_data[2 * gl_VertexIndex].xyz, 1.0);
  o_world = p.xyz;
  o_normal = mat3(pc.model) * vertex_data[2 * gl_VertexIndex + 1].xyz;  // rigid transforms only
  gl_Position = scene.view_proj * p;
}
