#version 460
#extension GL_GOOGLE_include_directive : require
// Scene meshes: Lambert + a soft Blinn highlight per light, shadowed lights through a 3x3 PCF of the shadow map
// (hardware depth comparison), which holds the head, the floor and the hair.
#include "render/scene/scene_layout.glsl"

layout(set = 0, binding = 2) uniform sampler2DShadow shadow_map;

layout(location = 0) in vec3 i_world;
layout(location = 1) in vec3 i_normal;
layout(location = 2) in float i_paint;
layout(location = 0) out vec4 o_color;

float shadow_factor(vec3 p, vec3 n, vec3 l) {
  if (scene.shadow_info.x < 0.5) return 1.0;
  const vec4 lc = scene.shadow_proj * vec4(p, 1.0);
  const vec3 ndc = lc.xyz / lc.w;
  const vec2 uv = ndc.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 1.0;
  const vec2 texel = 1.0 / vec2(textureSize(shadow_map, 0));
  // Slope-scaled bias in depth units: a couple of texels' worth of depth change across the surface.
  const float bias = scene.shadow_info.y * (1.0 + 2.0 * sqrt(max(0.0, 1.0 - dot(n, l) * dot(n, l))) / max(dot(n, l), 0.2));
  float sum = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) sum += texture(shadow_map, vec3(uv + vec2(x, y) * texel, ndc.z - bias));
  return sum / 9.0;
}

void main() {
  const vec3 n = normalize(i_normal);
  const vec3 v = normalize(scene.eye.xyz - i_world);
  // Painted vertices (the sample head's scalp) take a dark hair-root brown, so the skin under the hair does not
  // shine through it.
  const vec3 albedo = mix(pc.color.rgb, vec3(0.05, 0.028, 0.016), clamp(i_paint, 0.0, 1.0));
  vec3 color = scene.ambient.rgb * albedo;
  for (uint i = 0u; i < scene.counts.x; ++i) {
    vec3 l;
    float attenuation = 1.0;
    if (scene.light_pos[i].w < 0.5) {
      l = -scene.light_dir[i].xyz;
    } else {
      const vec3 to_light = scene.light_pos[i].xyz - i_world;
      const float dist = max(length(to_light), 1e-4);
      l = to_light / dist;
      attenuation = smoothstep(scene.light_cone[i].y, scene.light_cone[i].x, dot(-l, scene.light_dir[i].xyz)) /
                    (dist * dist);
    }
    const float ndl = max(dot(n, l), 0.0);
    if (ndl <= 0.0 || attenuation <= 0.0) continue;
    if (scene.light_color[i].w > 0.5) attenuation *= shadow_factor(i_world, n, l);
    const vec3 h = normalize(l + v);
    const float spec = pc.color.w * pow(max(dot(n, h), 0.0), 40.0);
    color += (albedo * ndl + spec * (1.0 - 0.8 * i_paint)) * scene.light_color[i].rgb * attenuation;
  }
  o_color = vec4(color, 1.0);
}
