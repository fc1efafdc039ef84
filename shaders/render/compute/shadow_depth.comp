#version 460
#extension GL_GOOGLE_include_directive : require
// tressvk_cmd_shadow_hair: hair depth into the host's shadow map, in compute. One thread per segment walks it in
// shadow-map texels (a sample per texel or less) and, at each sample, across its width (at least 1.5 texels, as
// the raster shadow pass draws it, so thin hair still lands in the map), keeps the nearest depth per texel
// (atomicMin on the float bits of depths in [0, 1], which order like the values) in a copy of the rectangle of the
// host's map the hair can reach (shadow.cpp, hair_rect; texels outside it are left alone).
layout(local_size_x = 64) in;
#include "render/hair_layout.glsl"

layout(std430, set = 0, binding = 5) buffer Depth { uint depth[]; };
layout(push_constant) uniform Shadow {
  uvec4 size;    // x: width, y: height of the map; z, w: the rectangle's first texel
  uvec4 params;  // x: the rectangle's width, y: strands drawn, z: the rectangle's height, w: segments
} pc;

vec4 to_map(uint strand, uint v, out float width_texels) {
  const uint n = dc.counts.x;
  const uint index = (strand / 32u) * (32u * n) + v * 32u + strand % 32u;
  const vec3 p = anchors[strand % dc.counts.y].xyz + positions[index].xyz;
  const vec4 c = dc.view_proj * vec4(p, 1.0);
  const float w = max(abs(c.w), 1e-6);
  const uint group = min(guide_info[strand % dc.counts.y].x, 15u);
  const Material m = dc.materials[group];
  const float along = float(v) / float(n - 1u);
  const float texels_per_metre = length(vec3(dc.view_proj[0].x, dc.view_proj[1].x, dc.view_proj[2].x)) * 0.5 *
                                 float(pc.size.x) / w;
  width_texels = m.shape.y * mix(1.0, m.shape.z, along) * dc.lod.x * texels_per_metre;
  return vec4((c.xy / w * 0.5 + 0.5) * vec2(pc.size.xy), c.z / w, c.w);
}

void main() {
  const uint n = dc.counts.x;
  const uint seg = gl_GlobalInvocationID.x;
  if (seg >= pc.params.w) return;
  const uint strand = seg / (n - 1u), i = seg % (n - 1u);
  float wa, wb;
  const vec4 a = to_map(strand, i, wa), b = to_map(strand, i + 1u, wb);
  if (a.w <= 0.0 || b.w <= 0.0) return;
  const vec2 d = b.xy - a.xy;
  const float len = length(d);
  const vec2 across = len > 1e-6 ? vec2(-d.y, d.x) / len : vec2(1.0, 0.0);
  const uint steps = min(uint(ceil(len)), 256u);
  const bool last = i + 2u >= n;  // the segment's end is the next one's start: only the last segment samples it
  for (uint k = 0u; k <= steps; ++k) {
    if (k == steps && steps > 0u && !last) break;
    const float t = steps == 0u ? 0.0 : float(k) / float(steps);
    const vec2 x = mix(a.xy, b.xy, t);
    const float z = mix(a.z, b.z, t);
    if (z < 0.0 || z > 1.0) continue;
    const float half_width = max(0.5 * mix(wa, wb, t), 0.75);
    const uint taps = uint(ceil(half_width));
    for (int o = -int(taps); o <= int(taps); ++o) {
      const vec2 y = x + across * (half_width * float(o) / float(taps));
      const vec2 q = y - vec2(pc.size.zw);  // in the rectangle's texels
      if (any(lessThan(q, vec2(0.0))) || any(greaterThanEqual(q, vec2(pc.params.xz)))) {
        // Inside the map but outside the rectangle: never, the rectangle being conservative; counted.
        if (all(greaterThanEqual(y, vec2(0.0))) && all(lessThan(y, vec2(pc.size.xy))))
          atomicAdd(depth[pc.size.x * pc.size.y], 1u);
        continue;
      }
      const uint texel = uint(q.y) * pc.params.x + uint(q.x);
      // Read first: most samples of dense hair are behind what the texel holds, and skip the atomic.
      if (depth[texel] > floatBitsToUint(z)) atomicMin(depth[texel], floatBitsToUint(z));
    }
  }
}
