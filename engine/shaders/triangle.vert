#version 450
// One triangle whose corners and colours come from push constants: the smallest draw that proves a graphics
// pipeline, dynamic rendering and readback work. No vertex buffers.
layout(push_constant) uniform Push {
  vec4 position[3];  // clip space
  vec4 color[3];     // linear RGBA
} pc;

layout(location = 0) out vec4 v_color;

void main() {
  gl_Position = pc.position[gl_VertexIndex];
  v_color = pc.color[gl_VertexIndex];
}
