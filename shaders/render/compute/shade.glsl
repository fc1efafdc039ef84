// Kajiya-Kay shading of a hair point for the compute path: the deep-opacity-map shadow below and the shared
// lighting (render/hair_lighting.glsl). Included by vertex.comp (per vertex, the default) and fine.comp (per
// fragment, TVK_RASTER_SHADE_PER_FRAGMENT) after render/compute/raster_layout.glsl.
#define TVK_SHADOWED 1
#define TVK_CUSTOM_SHADOW 1

// Light reaching p through the hair (deep opacity map) and past opaque occluders (the host's shadow map):
// - hair: over 3 x 3 map texels, the fibre density in front of p (the layers wholly in front of its depth behind
//   the nearest hair, and the part of its own layer in front of it, linearly), as optical depth
//   -ln(1 - fiber_alpha) per fully covering fibre;
// - opaque: the host map's 3 x 3 texels around p whose depth lies in front of p AND well in front of the hair's
//   nearest depth (so the hair the host also drew into its map is not taken for an opaque occluder).
float shadow_transmittance(vec3 p, Material m) {
  if ((pc.params.z & kFlagShadowed) == 0u) return 1.0;
  const vec4 lc = dc.shadow_proj * vec4(p, 1.0);
  const vec3 ndc = lc.xyz / lc.w;
  const vec2 uv = ndc.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || ndc.z > 1.0) return 1.0;
  const float here = light_metres(ndc.z);
  const float spacing = max(m.fiber.x * m.shape.y, 1e-7);
  const uint texels = kDomSize * kDomSize;
  const ivec2 centre = ivec2(uv * float(kDomSize));
  float density = 0.0;
  float hair_front = 1e30;
  [[unroll]] for (int y = -1; y <= 1; ++y) {
    [[unroll]] for (int x = -1; x <= 1; ++x) {
      const ivec2 at = clamp(centre + ivec2(x, y), ivec2(0), ivec2(kDomSize - 1u));
      const uint texel = uint(at.y) * kDomSize + uint(at.x);
      const float front = uintBitsToFloat(dom[texel]);
      hair_front = min(hair_front, front);
      const float behind = (here - front) / spacing - 1.0;  // one fibre of bias: a fibre never shadows itself
      if (behind <= 0.0) continue;
      const uvec4 layers = dom_layers[texels / 4u + texel];  // the texel's kDomLayers (4) layers in one load
      for (uint k = 0u; k < kDomLayers; ++k) {
        const float lo = kDomEdge[k], hi = kDomEdge[k + 1u];
        if (behind <= lo) break;
        const float part = k + 1u == kDomLayers ? 1.0 : clamp((behind - lo) / (hi - lo), 0.0, 1.0);
        density += part * float(layers[k]) / kDomUnit;
      }
    }
  }
  const float hair = exp(log(max(1.0 - m.fiber.y, 1e-6)) * density / 9.0);
  const ivec2 size = textureSize(shadow_map, 0);
  const ivec2 host_texel = ivec2(uv * vec2(size));
  const float opaque_margin = 4.0 * spacing;
  float lit = 0.0;
  [[unroll]] for (int y = -1; y <= 1; ++y) {
    [[unroll]] for (int x = -1; x <= 1; ++x) {
      const float occluder = light_metres(texelFetch(shadow_map, clamp(host_texel + ivec2(x, y), ivec2(0), size - 1), 0).r);
      lit += (occluder < here - 1.5 * spacing && occluder < hair_front - opaque_margin) ? 0.0 : 1.0;
    }
  }
  return hair * lit / 9.0;
}

#include "render/hair_lighting.glsl"

