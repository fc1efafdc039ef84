#version 460
#extension GL_GOOGLE_include_directive : require
// Compute rasterizer, pass 1: per drawn vertex, its screen position, depth and projected width (with the LOD
// widening that keeps the coverage), and its Kajiya-Kay colour (shaded per vertex, interpolated along segments).
layout(local_size_x = 64) in;
#include "render/compute/raster_layout.glsl"

#include "render/compute/shade.glsl"

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
  // Reversed submission (order-independence test): the same strands written in the opposite order.
  const uint slot = (pc.params.z & kFlagReverse) != 0u ? (drawn - 1u - strand) * n + v : id;
  const bool per_fragment = (pc.params.z & kFlagPerFragment) != 0u;
  // Shaded per fragment: the point and tangent for fine.comp, after the drawn vertices; the vertex colour then
  // only for a captured frame (the reference shades per vertex).
  vec3 color = vec3(0.0);
  if (!per_fragment || (pc.params.z & kFlagCapture) != 0u) color = shade_hair(position, tangent, along, m, tint);
  if (per_fragment) {
    verts[2u * (drawn * n + slot)] = vec4(position, along);
    verts[2u * (drawn * n + slot) + 1u] = vec4(tangent, tint);
  }
  verts[2u * slot] = screen;
  verts[2u * slot + 1u] = vec4(color, m.shape.w);
}
