#version 460
// Composite of the compute rasterizer's hair layer: one full-screen triangle.
void main() {
  const vec2 uv = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
  gl_Position = vec4(uv * 2.0 - 1.0, 0.0, 1.0);
}
