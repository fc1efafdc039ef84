#version 460
#extension GL_GOOGLE_include_directive : require
// Compute rasterizer, vertex shading: per drawn vertex its Kajiya-Kay colour (shaded per vertex, interpolated along
// segments), beside the scan (which reads no vertex), once the deep opacity map is built: only the fine pass reads
// the colour, so the shading is no longer a step of its own before the binning.
layout(local_size_x = 64) in;
#include "render/compute/raster_layout.glsl"

#include "render/compute/shade.glsl"
#include "render/compute/vertex_input.glsl"

void main() {
  const uint id = gl_GlobalInvocationID.x;
  if (id >= pc.params.y * dc.counts.x) return;
  const DrawnVertex d = drawn_vertex(id);
  // Shaded per fragment, the vertex colour only for a captured frame (the reference shades per vertex).
  vec3 color = vec3(0.0);
  if ((pc.params.z & kFlagPerFragment) == 0u || (pc.params.z & kFlagCapture) != 0u)
    color = shade_hair(d.position, d.tangent, d.along, d.material, d.tint);
  verts[2u * d.slot + 1u] = vec4(color, d.material.shape.w);
}
