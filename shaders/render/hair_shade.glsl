// Hair shading: analytic coverage, Kajiya-Kay diffuse + two shifted highlights over several lights, and shadow-
// map lookup with fibre-count self-shadowing. Included by hair.frag (unshadowed) and hair_shadowed.frag (which
// defines TVK_SHADOWED first).
#include "render/hair_layout.glsl"

// 0: the opaque core (fully covered pixels, depth written); 1: the blended fringe (partial coverage).
layout(constant_id = 0) const uint kPass = 0u;
// Coverage at and above which a fragment belongs to the opaque core.
const float kCoreCoverage = 0.98;

#ifdef TVK_SHADOWED
layout(set = 0, binding = TVK_DRAW_BINDING_SHADOW_MAP) uniform sampler2D shadow_map;
#endif

layout(location = 0) in vec3 i_position;
layout(location = 1) in vec3 i_tangent;
layout(location = 2) noperspective in float i_offset_px;
layout(location = 3) noperspective in float i_width_px;
layout(location = 4) in float i_along;
layout(location = 5) flat in uint i_group;
layout(location = 6) flat in float i_tint;

layout(location = 0) out vec4 o_color;

// Fraction of a one-pixel-wide box centred at distance d from the centre line covered by a strip of width w
// (both in pixels): the overlap of [d - w/2, d + w/2] with [-1/2, 1/2]. Integrated across the strand it gives
// exactly w, so a strand thinner than a pixel keeps its total coverage wherever it falls: no shimmer, no gaps.
float coverage(float d, float w) { return clamp(min(d + 0.5 * w, 0.5) - max(d - 0.5 * w, -0.5), 0.0, 1.0); }

#include "render/hair_lighting.glsl"

void main() {
  const Material m = dc.materials[i_group];
  const float alpha = coverage(abs(i_offset_px), i_width_px) * m.shape.w;
  if (kPass == 0u) {
    if (alpha < kCoreCoverage) discard;
  } else {
    if (alpha >= kCoreCoverage || alpha < 1.0 / 255.0) discard;
  }

  const vec3 color = shade_hair(i_position, i_tangent, i_along, m, i_tint);
  o_color = kPass == 0u ? vec4(color, 1.0) : vec4(color * alpha, alpha);  // premultiplied
}
