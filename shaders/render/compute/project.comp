#version 460
#extension GL_GOOGLE_include_directive : require
// Compute rasterizer, vertex projection: per drawn vertex its screen position, depth and projected width (with the
// LOD widening that keeps the coverage), which the binning passes and the fine pass read; shaded per fragment,
// also its point and tangent for the fine pass. No lighting here (vertex.comp), so nothing of the deep opacity map
// is read and the projection runs beside the map's first pass.
layout(local_size_x = 64) in;
#include "render/compute/raster_layout.glsl"

#include "render/compute/vertex_input.glsl"

void main() {
  const uint n = dc.counts.x;
  const uint drawn = pc.params.y;
  const uint id = gl_GlobalInvocationID.x;
  if (id >= drawn * n) return;
  const DrawnVertex d = drawn_vertex(id);
  const Material m = d.material;
  const float width = m.shape.y * mix(1.0, m.shape.z, d.along) * dc.lod.x;
  const vec4 clip = dc.view_proj * vec4(d.position, 1.0);
  const vec2 half_viewport = 0.5 * dc.viewport.xy;
  vec4 screen = vec4(0.0, 0.0, -1.0, 0.0);  // depth -1: behind the eye, the segment is culled
  if (clip.w > 1e-6) {
    const float w = clip.w;
    const vec3 to_eye = dc.eye.w > 0.5 ? -dc.view_dir.xyz : dc.eye.xyz - d.position;
    vec3 right = cross(d.tangent, to_eye);
    const float right_len = length(right);
    right = right_len > 1e-12 ? right / right_len : vec3(0.0);
    const vec4 cr = dc.view_proj * vec4(right, 0.0);
    const vec2 screen_r = (cr.xy * w - clip.xy * cr.w) / (w * w) * half_viewport;
    const vec3 ndc = clip.xyz / w;
    screen = vec4((ndc.xy + 1.0) * half_viewport, ndc.z, width * length(screen_r));
  }
  // Shaded per fragment: the point and tangent for fine.comp, after the drawn vertices.
  if ((pc.params.z & kFlagPerFragment) != 0u) {
    verts[2u * (drawn * n + d.slot)] = vec4(d.position, d.along);
    verts[2u * (drawn * n + d.slot) + 1u] = vec4(d.tangent, d.tint);
  }
  verts[2u * d.slot] = screen;
}
