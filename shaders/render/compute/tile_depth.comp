#version 460
#extension GL_GOOGLE_include_directive : require
// Compute rasterizer, pass 1 (beside vertex.comp): the farthest host depth of each 8 x 8 tile, so that binning
// drops segments hidden behind the host's opaque geometry in that whole tile.
layout(local_size_x = 8, local_size_y = 8) in;
#include "render/compute/raster_layout.glsl"

shared uint s_max;

void main() {
  if (gl_LocalInvocationIndex == 0u) s_max = 0u;
  barrier();
  const uvec2 p = gl_GlobalInvocationID.xy;
  // Depths are in [0, 1]: their float bits order like the values. Pixels outside the view do not count.
  if (p.x < pc.size.x && p.y < pc.size.y)
    atomicMax(s_max, floatBitsToUint(max(texelFetch(host_depth, ivec2(p), 0).r, 0.0)));
  barrier();
  if (gl_LocalInvocationIndex == 0u) {
    const uint tiles_count = pc.size.z * pc.size.w;
    tiles[3u * tiles_count + gl_WorkGroupID.y * pc.size.z + gl_WorkGroupID.x] = s_max;
  }
}
