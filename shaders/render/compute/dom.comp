#version 460
#extension GL_GOOGLE_include_directive : require
// Compute rasterizer, shadow passes (before vertex shading, only with a shadow map): the deep opacity map of the
// hair seen from the shadowed light. One thread per segment walks it in light-space texels (a sample per texel
// or less, ends included) and, in pass kPass = 0, keeps each texel's nearest hair depth (atomicMin); in pass 1
// adds the fibre's covered fraction of the texel (its width in texels times its length per sample) to the layer
// its depth behind that nearest hair falls into (atomicAdd, fixed point). Pass 2, beside the scatter pass once the
// vertex shading has read the map, clears it for the next call (nearest hair +infinity, densities 0): the next
// call then starts with pass 0, without a clear and a barrier of its own before it.
layout(local_size_x = 64) in;
layout(constant_id = 0) const uint kPass = 0u;
#include "render/compute/raster_layout.glsl"

struct LightPoint {
  vec2 texel;      // light-map texel coordinates
  float depth;     // metres from the light's near plane
  float per_metre; // texels per metre across the light direction here
};

LightPoint to_light(uint strand, uint v) {
  const uint n = dc.counts.x;
  const uint index = (strand / 32u) * (32u * n) + v * 32u + strand % 32u;
  const vec3 p = anchors[strand % dc.counts.y].xyz + positions[index].xyz;
  const vec4 lc = dc.shadow_proj * vec4(p, 1.0);
  const float w = max(abs(lc.w), 1e-6);
  LightPoint l;
  l.texel = (lc.xy / w * 0.5 + 0.5) * float(kDomSize);
  l.depth = light_metres(lc.z / w);
  l.per_metre = length(vec3(dc.shadow_proj[0].x, dc.shadow_proj[1].x, dc.shadow_proj[2].x)) * 0.5 *
                float(kDomSize) / w;
  return l;
}

void main() {
  if (kPass == 2u) {
    const uint texels = kDomSize * kDomSize;
    for (uint k = gl_GlobalInvocationID.x; k < texels * (1u + kDomLayers); k += 64u * gl_NumWorkGroups.x)
      dom[k] = k < texels ? 0x7f800000u : 0u;
    return;
  }
  const uint n = dc.counts.x;
  const uint seg = gl_GlobalInvocationID.x;
  if (seg >= pc.params.w) return;
  const uint strand = seg / (n - 1u), i = seg % (n - 1u);
  const LightPoint a = to_light(strand, i), b = to_light(strand, i + 1u);
  const float len = length(b.texel - a.texel);
  const uint steps = min(uint(ceil(len)), 64u);
  const uint group = min(guide_info[strand % dc.counts.y].x, 15u);
  const Material m = dc.materials[group];
  const float spacing = max(m.fiber.x * m.shape.y, 1e-7);  // metres of depth per fibre
  const uint texels = kDomSize * kDomSize;
  // A segment's end is the next segment's start: only the strand's last segment samples its end, and in pass 1
  // a start adds the half-sample the previous segment's end would have added (a quarter to a third fewer samples
  // and atomics; the same map in pass 0, the same densities to the fixed point's rounding in pass 1).
  const bool last = i + 2u >= n;
  float prev_piece = 0.0;
  if (kPass == 1u && i > 0u) {
    const LightPoint p = to_light(strand, i - 1u);
    const float plen = length(a.texel - p.texel);
    const uint psteps = min(uint(ceil(plen)), 64u);
    prev_piece = psteps == 0u ? 0.0 : plen / float(psteps);
  }
  for (uint k = 0u; k <= steps; ++k) {
    if (k == steps && steps > 0u && !last) break;
    const float t = steps == 0u ? 0.0 : float(k) / float(steps);
    const vec2 x = mix(a.texel, b.texel, t);
    if (any(lessThan(x, vec2(0.0))) || any(greaterThanEqual(x, vec2(kDomSize)))) continue;
    const uint texel = uint(x.y) * kDomSize + uint(x.x);
    const float depth = mix(a.depth, b.depth, t);
    if (kPass == 0u) {
      const uint bits = floatBitsToUint(max(depth, 0.0));
      if (dom[texel] > bits) atomicMin(dom[texel], bits);  // read first: skip the atomic when already nearer
    } else {
      const float along = float(i + uint(t > 0.5)) / float(n - 1u);
      const float width = m.shape.y * mix(1.0, m.shape.z, along) * dc.lod.x * mix(a.per_metre, b.per_metre, t);
      // Covered fraction of the texel: width (texels) x length per sample (texels), ends counted half.
      float piece = (steps == 0u ? 0.0 : len / float(steps)) * ((k == 0u || k == steps) ? 0.5 : 1.0);
      if (k == 0u) piece += 0.5 * prev_piece;
      const float cover = min(width, 1.0) * piece;
      if (cover <= 0.0) continue;
      const float behind = (depth - uintBitsToFloat(dom[texel])) / spacing;
      uint layer = 0u;
      while (layer + 1u < kDomLayers && behind >= kDomEdge[layer + 1u]) ++layer;
      atomicAdd(dom[texels + kDomLayers * texel + layer], uint(cover * kDomUnit + 0.5));
    }
  }
}
