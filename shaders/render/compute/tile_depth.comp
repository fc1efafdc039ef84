#version 460
#extension GL_GOOGLE_include_directive : require
// Compute rasterizer, pass 1 (beside vertex.comp): the farthest host depth of each 8 x 8 tile, so that binning
// drops segments hidden behind the host's opaque geometry in that whole tile. A workgroup takes a row of 8 tiles,
// a thread one pixel column of a tile (its 8 loads in flight together, each row of loads coalesced across the
// threads): 8 times fewer workgroups than one per tile, whose launches and barriers were most of this pass's time.
// It also starts the call's counting (it runs in the first step, before the count pass): every tile's segment
// count, the fine pass's tiles per weight bucket, the statistics counters and the composite's draw (0 vertices, 1
// instance) to zero, instead of transfer
// fills and a barrier of their own before the first pass.
layout(local_size_x = 64) in;
#include "render/compute/raster_layout.glsl"

shared uint s_max[8];

void main() {
  const uint lid = gl_LocalInvocationIndex;
  if (lid < 8u) s_max[lid] = 0u;
  barrier();
  const uint x = gl_WorkGroupID.x * 64u + lid;
  const uint y0 = gl_WorkGroupID.y * kTile;
  // Depths are in [0, 1]: their float bits order like the values. Pixels outside the view do not count.
  uint m = 0u;
  if (x < pc.size.x) {
    for (uint r = 0u; r < kTile; ++r) {
      if (y0 + r < pc.size.y) m = max(m, floatBitsToUint(max(texelFetch(host_depth, ivec2(x, y0 + r), 0).r, 0.0)));
    }
  }
  atomicMax(s_max[lid / kTile], m);
  barrier();
  const uint tx = gl_WorkGroupID.x * 8u + lid;
  if (lid < 8u && tx < pc.size.z) {
    const uint tiles_count = pc.size.z * pc.size.w;
    tiles[3u * tiles_count + gl_WorkGroupID.y * pc.size.z + tx] = s_max[lid];
    tiles[gl_WorkGroupID.y * pc.size.z + tx] = 0u;
  }
  if (gl_WorkGroupID.x == 0u && gl_WorkGroupID.y == 0u) {
    if (lid < 8u) counters[lid] = 0u;  // kCounterCount
    const uint tiles_count = pc.size.z * pc.size.w;
    for (uint b = lid; b < kBuckets; b += 64u) tiles[tile_list_buckets_at(tiles_count) + b] = 0u;
    if (lid == 0u) tiles[tile_list_at(tiles_count) + 4u] = 0u;  // tiles over kSplitFewAt entries (scan.comp)
    const uint at = pc.size.x * pc.size.y;  // after the layer: VkDrawIndirectCommand (fine.comp adds 6 per tile)
    if (lid == 0u) image[at] = uvec2(0u, 1u);
    if (lid == 1u) image[at + 1u] = uvec2(0u);
  }
}
