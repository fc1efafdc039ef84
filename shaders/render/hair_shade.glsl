// Hair shading: analytic coverage, Kajiya-Kay diffuse + two shifted highlights over several lights, and shadow-
// map lookup with fibre-count self-shadowing. Included by hair.frag (unshadowed) and hair_shadowed.frag (which
// defines TVK_SHADOWED first).
#include "render/hair_layout.glsl"

// 0: the opaque core (fully covered pixels, depth written); 1: the blended fringe (partial coverage).
layout(constant_id = 0) const uint kPass = 0u;
// Coverage at and above which a fragment belongs to the opaque core.
const float kCoreCoverage = 0.98;

#ifdef TVK_SHADOWED
layout(set = 0, binding = 5) uniform sampler2D shadow_map;
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

#ifdef TVK_SHADOWED
float linear_depth(float z) {
  const float n = dc.shadow_params.x, f = dc.shadow_params.y;
  return dc.shadow_params.z > 0.5 ? n * f / max(f - z * (f - n), 1e-12) : n + z * (f - n);
}

// Light reaching this point: 3x3 taps of the shadow map; each occluded tap counts the fibres between the
// occluder and the point from their depth difference (TressFX's approximation) and transmits
// (1 - fibre_alpha)^fibres. An opaque occluder (the head) is far in front, so it transmits ~0.
float shadow_transmittance(vec3 p, Material m) {
  const vec4 lc = dc.shadow_proj * vec4(p, 1.0);
  const vec3 ndc = lc.xyz / lc.w;
  const vec2 uv = ndc.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || ndc.z > 1.0) return 1.0;
  const ivec2 size = textureSize(shadow_map, 0);
  const ivec2 texel = ivec2(uv * vec2(size));
  const float here = linear_depth(ndc.z);
  const float fibre = max(m.fiber.x * m.shape.y, 1e-7);  // metres of depth per fibre
  const float bias = 1.5 * fibre;  // the hair's own depth in the map never counts as an occluder
  float sum = 0.0;
  [[unroll]] for (int y = -1; y <= 1; ++y) {
    [[unroll]] for (int x = -1; x <= 1; ++x) {
      const ivec2 at = clamp(texel + ivec2(x, y), ivec2(0), size - 1);
      const float dz = here - linear_depth(texelFetch(shadow_map, at, 0).r) - bias;
      sum += dz <= 0.0 ? 1.0 : pow(1.0 - m.fiber.y, max(1.0, dz / fibre));
    }
  }
  return sum / 9.0;
}
#endif

void main() {
  const Material m = dc.materials[i_group];
  const float alpha = coverage(abs(i_offset_px), i_width_px) * m.shape.w;
  if (kPass == 0u) {
    if (alpha < kCoreCoverage) discard;
  } else {
    if (alpha >= kCoreCoverage || alpha < 1.0 / 255.0) discard;
  }

  const vec3 base = mix(m.base.rgb, m.tip.rgb, i_along) * i_tint;
  const vec3 t = normalize(i_tangent);
  const vec3 e = dc.eye.w > 0.5 ? -dc.view_dir.xyz : normalize(dc.eye.xyz - i_position);
  const float te = clamp(dot(t, e), -1.0, 1.0);
  const float theta_e = acos(te);
  vec3 color = dc.ambient.rgb * m.base.w * base;
  for (uint i = 0u; i < dc.counts.w; ++i) {
    const Light light = dc.lights[i];
    vec3 l;
    float attenuation = 1.0;
    if (light.position.w < 0.5) {
      l = -light.direction.xyz;
    } else {
      const vec3 to_light = light.position.xyz - i_position;
      const float dist = max(length(to_light), 1e-4);
      l = to_light / dist;
      attenuation = smoothstep(light.cone.y, light.cone.x, dot(-l, light.direction.xyz)) / (dist * dist);
      if (light.direction.w > 0.0) {
        const float r = clamp(1.0 - pow(dist / light.direction.w, 4.0), 0.0, 1.0);
        attenuation *= r * r;
      }
    }
#ifdef TVK_SHADOWED
    if (light.color.w > 0.5) attenuation *= shadow_transmittance(i_position, m);
#endif
    if (attenuation <= 0.0) continue;
    const float tl = clamp(dot(t, l), -1.0, 1.0);
    // Kajiya-Kay: diffuse from the sine of the tangent-light angle; a highlight where the eye lies on the cone of
    // reflected light, i.e. where theta_l + theta_e = pi, each highlight shifted by its cuticle tilt.
    const float diffuse = sqrt(max(0.0, 1.0 - tl * tl));
    const float theta = acos(tl) + theta_e;
    const float spec1 = pow(max(0.0, -cos(theta + m.spec.w)), m.spec.x);
    const float spec2 = pow(max(0.0, -cos(theta + m.shape.x)), m.spec.z);
    color += (m.base.w * diffuse * base + m.tip.w * spec1 + m.spec.y * spec2 * base) * light.color.rgb * attenuation;
  }
  o_color = kPass == 0u ? vec4(color, 1.0) : vec4(color * alpha, alpha);  // premultiplied
}
