#version 460
#extension GL_GOOGLE_include_directive : require
// Scene meshes into the shadow map (depth only).
#include "render/scene/scene_layout.glsl"

void main() {
  const vec4 p = pc.model * vec4(vertex_data[2 * gl_VertexIndex].xyz, 1.0);
  gl_Position = scene.shadow_proj * p;
}
