#version 460
// Composite of the compute rasterizer's hair layer into the host's colour target: premultiplied "over" (blend
// ONE, ONE_MINUS_SRC_ALPHA), one texel of the layer per pixel.
layout(std430, set = 0, binding = 0) readonly buffer Image { uvec2 image[]; };
layout(push_constant) uniform Composite { uvec4 size; } pc;  // x: width, y: height
layout(location = 0) out vec4 o_color;

void main() {
  const uvec2 p = uvec2(gl_FragCoord.xy);
  if (p.x >= pc.size.x || p.y >= pc.size.y) discard;
  const uvec2 v = image[p.y * pc.size.x + p.x];
  const vec4 c = vec4(unpackHalf2x16(v.x), unpackHalf2x16(v.y));
  if (c.a <= 0.0) discard;
  o_color = c;
}
