#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Compute rasterizer, pass 3: exclusive prefix sum of the tiles' segment counts -> first entry and scatter cursor
// per tile, and the work items of the over-full tiles. One workgroup of 1024 threads; thread i owns the run of
// ceil(tiles / 1024) consecutive tiles starting at i times that (1080p: 32 tiles, 4K: 127): it sums its run (loads
// issued kAhead at a time, so their latencies overlap), one workgroup scan of the 1024 sums (a subgroup scan, then
// a scan of the subgroups' sums by the first subgroup) gives the run's offset, and the thread walks its run again
// writing each tile's offset. Two barriers in all, where a walk over blocks of 1024 tiles needed three per block.
// A tile with more than kSplitAt entries is split into ceil(count / kSplit) work items (fine.comp composites each
// item's share of the tile's depth range in its own workgroup and the last one to finish merges them): the same
// scan numbers their slots, each such tile writes its items (tile, index) into the split list, and the indirect
// dispatch size of the split pass is the number of slots used. A tile whose items would not fit in the slots
// (pc.split.x) stays whole (slower, never wrong).
layout(local_size_x = 1024) in;
#include "render/compute/raster_layout.glsl"

const uint kAhead = 8u;
shared uvec2 s_sub[1024];  // per subgroup: its sums, then the sums of the subgroups before it
shared uvec2 s_total;      // all tiles' entries and split slots
shared uint s_used;        // split slots used

uint items_of(uint v) { return v > kSplitAt ? (v + kSplit - 1u) / kSplit : 0u; }  // work items of an over-full tile

void main() {
  const uint tiles_count = pc.size.z * pc.size.w;
  const uint i = gl_LocalInvocationIndex;
  const uint run = (tiles_count + 1023u) / 1024u;
  const uint t0 = min(i * run, tiles_count), t1 = min(t0 + run, tiles_count);
  if (i == 0u) s_used = 0u;
  uvec2 sum = uvec2(0u);
  for (uint t = t0; t < t1; t += kAhead) {
    uint ahead[kAhead];
    for (uint a = 0u; a < kAhead; ++a) ahead[a] = t + a < t1 ? tiles[t + a] : 0u;
    for (uint a = 0u; a < kAhead; ++a) sum += uvec2(ahead[a], items_of(ahead[a]));
  }
  const uvec2 inclusive = subgroupInclusiveAdd(sum);
  if (gl_SubgroupInvocationID == gl_SubgroupSize - 1u) s_sub[gl_SubgroupID] = inclusive;
  barrier();
  if (gl_SubgroupID == 0u) {
    uvec2 acc = uvec2(0u);
    for (uint w0 = 0u; w0 < gl_NumSubgroups; w0 += gl_SubgroupSize) {
      const uint w = w0 + gl_SubgroupInvocationID;
      const uvec2 x = w < gl_NumSubgroups ? s_sub[w] : uvec2(0u);
      const uvec2 before = subgroupExclusiveAdd(x);
      if (w < gl_NumSubgroups) s_sub[w] = acc + before;
      acc += subgroupAdd(x);
    }
    if (subgroupElect()) s_total = acc;
  }
  barrier();
  uvec2 offset = s_sub[gl_SubgroupID] + inclusive - sum;
  uint used = 0u;
  for (uint t = t0; t < t1; t += kAhead) {
    uint ahead[kAhead];
    for (uint a = 0u; a < kAhead; ++a) ahead[a] = t + a < t1 ? tiles[t + a] : 0u;
    for (uint a = 0u; a < kAhead && t + a < t1; ++a) {
      const uint tile = t + a, v = ahead[a], k = items_of(v);
      tiles[tiles_count + tile] = offset.x;
      tiles[2u * tiles_count + tile] = offset.x;
      const bool split = k > 0u && offset.y + k <= pc.split.x;
      tiles[4u * tiles_count + tile] = split ? offset.y : kNotSplit;
      tiles[5u * tiles_count + tile] = 0u;  // items of the tile finished (fine.comp)
      if (split) {
        for (uint j = 0u; j < k; ++j) split_items[2u + offset.y + j] = uvec2(tile, j);
        used = offset.y + k;
      }
      offset += uvec2(v, k);
    }
  }
  if (used > 0u) atomicMax(s_used, used);
  barrier();
  if (i == 0u) {
    if (s_total.x > pc.params.x) counters[1] = s_total.x - pc.params.x;  // entries that did not fit
    split_items[0] = uvec2(s_used, 1u);  // the split pass's indirect dispatch: (slots used, 1, 1)
    split_items[1] = uvec2(1u, 0u);
  }
}
