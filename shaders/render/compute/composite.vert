#version 460
// Composite of the compute rasterizer's hair layer: a quad per tile with hair. fine.comp appends each such tile
// after the layer's pixels and counts 6 vertices per tile into the VkDrawIndirectCommand before the list, so
// nothing is drawn over tiles without hair. (A full-screen triangle cost 0.17 ms at 1080p on an NVIDIA H100, a
// GPU with little raster hardware, most of it on empty pixels; the rectangle around the hair still covered empty
// tiles between strands.)
layout(std430, set = 0, binding = 0) readonly buffer Image { uvec2 image[]; };
layout(push_constant) uniform Composite { uvec4 size; } pc;  // x: width, y: height

void main() {
  const uint at = pc.size.x * pc.size.y;
  const uint v = uint(gl_VertexIndex);
  const uvec2 tile = image[at + 2u + v / 6u];
  const uint c = v % 6u;  // two triangles: (0,0) (1,0) (0,1), (1,0) (1,1) (0,1)
  const vec2 corner = vec2(c == 1u || c == 3u || c == 4u ? 1.0 : 0.0, c == 2u || c >= 4u ? 1.0 : 0.0);
  const vec2 px = min((vec2(tile) + corner) * 8.0, vec2(pc.size.xy));  // 8 x 8 pixel tiles
  gl_Position = vec4(px / vec2(pc.size.xy) * 2.0 - 1.0, 0.0, 1.0);
}
