#version 460
#extension GL_GOOGLE_include_directive : require
// Compute rasterizer, pass 1: per drawn vertex, its screen position, depth and projected width (with the LOD
// widening that keeps the coverage), and its Kajiya-Kay colour (shaded per vertex, interpolated along segments).
layout(local_size_x = 64) in;
#define TVK_SHADOWED 1
#define TVK_CUSTOM_SHADOW 1
#include "render/compute/raster_layout.glsl"

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
      for (uint k = 0u; k < kDomLayers; ++k) {
        const float lo = kDomEdge[k], hi = kDomEdge[k + 1u];
        if (behind <= lo) break;
        const float part = k + 1u == kDomLayers ? 1.0 : clamp((behind - lo) / (hi - lo), 0.0, 1.0);
        density += part * float(dom[texels * (1u + k) + texel]) / kDomUnit;
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

float strand_hash(uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return float(x) * (1.0 / 4294967296.0);
}

void main() {
  const uint n = dc.counts.x;
  const uint drawn = pc.params.y;
  const uint id = gl_GlobalInvocationID.x;
  if (id >= drawn * n) return;
  const uint strand = id / n;
  const uint v = id % n;
  // The blocked layout of the simulation (TVK_STRAND_BLOCK = 32).
  const uint index = (strand / 32u) * (32u * n) + v * 32u + strand % 32u;
  const vec3 position = anchors[strand % dc.counts.y].xyz + positions[index].xyz;
  const vec3 tangent = tangents[index].xyz;
  const float along = float(v) / float(n - 1u);
  const uint group = min(guide_info[strand % dc.counts.y].x, 15u);
  const Material m = dc.materials[group];
  const float tint = 1.0 + m.fiber.z * (2.0 * strand_hash(strand) - 1.0);
  const float width = m.shape.y * mix(1.0, m.shape.z, along) * dc.lod.x;

  const vec4 clip = dc.view_proj * vec4(position, 1.0);
  const vec2 half_viewport = 0.5 * dc.viewport.xy;
  vec4 screen = vec4(0.0, 0.0, -1.0, 0.0);  // depth -1: behind the eye, the segment is culled
  if (clip.w > 1e-6) {
    const float w = clip.w;
    const vec3 to_eye = dc.eye.w > 0.5 ? -dc.view_dir.xyz : dc.eye.xyz - position;
    vec3 right = cross(tangent, to_eye);
    const float right_len = length(right);
    right = right_len > 1e-12 ? right / right_len : vec3(0.0);
    const vec4 cr = dc.view_proj * vec4(right, 0.0);
    const vec2 screen_r = (cr.xy * w - clip.xy * cr.w) / (w * w) * half_viewport;
    const vec3 ndc = clip.xyz / w;
    screen = vec4((ndc.xy + 1.0) * half_viewport, ndc.z, width * length(screen_r));
  }
  vec3 color = shade_hair(position, tangent, along, m, tint);
  // Reversed submission (order-independence test): the same strands written in the opposite order.
  const uint slot = (pc.params.z & kFlagReverse) != 0u ? (drawn - 1u - strand) * n + v : id;
  verts[2u * slot] = screen;
  verts[2u * slot + 1u] = vec4(color, m.shape.w);
}
