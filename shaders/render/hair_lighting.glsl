// Kajiya-Kay lighting of a hair point and the fibre-count shadow lookup, shared by the raster path's fragment
// shader (hair_shade.glsl) and the compute path's per-vertex shading (compute/vertex.comp). The includer declares
// `dc` (hair_layout.glsl) and, with TVK_SHADOWED, `shadow_map`.
#if defined(TVK_SHADOWED) && !defined(TVK_CUSTOM_SHADOW)
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

// Linear RGB leaving a hair point toward the eye: ambient plus, per light, Kajiya-Kay diffuse and two shifted
// highlights, attenuated by the spot cone, distance and shadow.
vec3 shade_hair(vec3 position, vec3 tangent, float along, Material m, float tint) {
  const vec3 base = mix(m.base.rgb, m.tip.rgb, along) * tint;
  const vec3 t = normalize(tangent);
  const vec3 e = dc.eye.w > 0.5 ? -dc.view_dir.xyz : normalize(dc.eye.xyz - position);
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
      const vec3 to_light = light.position.xyz - position;
      const float dist = max(length(to_light), 1e-4);
      l = to_light / dist;
      attenuation = smoothstep(light.cone.y, light.cone.x, dot(-l, light.direction.xyz)) / (dist * dist);
      if (light.direction.w > 0.0) {
        const float r = clamp(1.0 - pow(dist / light.direction.w, 4.0), 0.0, 1.0);
        attenuation *= r * r;
      }
    }
#ifdef TVK_SHADOWED
    if (light.color.w > 0.5) attenuation *= shadow_transmittance(position, m);
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
  return color;
}
