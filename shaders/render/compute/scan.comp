#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Compute rasterizer, pass 3: exclusive prefix sum of the tiles' segment counts -> first entry and scatter cursor
// per tile, and the work items of the over-full tiles. One workgroup of 1024 threads walks the tiles in blocks of
// 1024 (1080p: 32 blocks): each thread loads one tile per block (consecutive threads, consecutive tiles:
// coalesced; kAhead blocks' loads issued together, so their latencies overlap instead of adding up), a subgroup
// scan, a scan of the subgroups' sums by the first subgroup, and the running total of the earlier blocks give its
// offset.
// A tile with more than kSplitAt entries is split into ceil(count / kSplit) work items (fine.comp composites each
// item's share of the tile's depth range in its own workgroup and the last one to finish merges them): the same
// scan numbers their slots, each such tile writes its items (tile, index) into the split list, and the indirect
// dispatch size of the split pass is the number of slots used. A tile whose items would not fit in the slots
// (pc.split.x) stays whole (slower, never wrong).
layout(local_size_x = 1024) in;
#include "render/compute/raster_layout.glsl"

const uint kAhead = 8u;
shared uvec2 s_sub[1024];  // per subgroup: its sums, then the sums of the subgroups before it
shared uvec2 s_block;      // the block's totals
shared uint s_used;        // split slots used

void main() {
  const uint tiles_count = pc.size.z * pc.size.w;
  const uint i = gl_LocalInvocationIndex;
  uvec2 carry = uvec2(0u);  // entries and split slots of the earlier blocks
  if (i == 0u) s_used = 0u;
  for (uint group = 0u; group < tiles_count; group += kAhead * 1024u) {
    uint ahead[kAhead];
    for (uint a = 0u; a < kAhead; ++a) {
      const uint t = group + a * 1024u + i;
      ahead[a] = t < tiles_count ? tiles[t] : 0u;
    }
    for (uint a = 0u; a < kAhead; ++a) {
      const uint t = group + a * 1024u + i;
      if (group + a * 1024u >= tiles_count) break;  // uniform
      const uint v = ahead[a];
      const uint k = v > kSplitAt ? (v + kSplit - 1u) / kSplit : 0u;  // work items of an over-full tile
      const uvec2 inclusive = subgroupInclusiveAdd(uvec2(v, k));
      if (gl_SubgroupInvocationID == gl_SubgroupSize - 1u) s_sub[gl_SubgroupID] = inclusive;
      barrier();
      if (gl_SubgroupID == 0u) {
        uvec2 run = uvec2(0u);
        for (uint w0 = 0u; w0 < gl_NumSubgroups; w0 += gl_SubgroupSize) {
          const uint w = w0 + gl_SubgroupInvocationID;
          const uvec2 x = w < gl_NumSubgroups ? s_sub[w] : uvec2(0u);
          const uvec2 before = subgroupExclusiveAdd(x);
          if (w < gl_NumSubgroups) s_sub[w] = run + before;
          run += subgroupAdd(x);
        }
        if (subgroupElect()) s_block = run;
      }
      barrier();
      const uvec2 offset = carry + s_sub[gl_SubgroupID] + inclusive - uvec2(v, k);
      if (t < tiles_count) {
        tiles[tiles_count + t] = offset.x;
        tiles[2u * tiles_count + t] = offset.x;
        const bool split = k > 0u && offset.y + k <= pc.split.x;
        tiles[4u * tiles_count + t] = split ? offset.y : kNotSplit;
        tiles[5u * tiles_count + t] = 0u;  // items of the tile finished (fine.comp)
        if (split) {
          for (uint j = 0u; j < k; ++j) split_items[2u + offset.y + j] = uvec2(t, j);
          atomicMax(s_used, offset.y + k);
        }
      }
      carry += s_block;
      barrier();  // s_sub and s_block are rewritten by the next block
    }
  }
  if (i == 0u) {
    if (carry.x > pc.params.x) counters[1] = carry.x - pc.params.x;  // entries that did not fit
    split_items[0] = uvec2(s_used, 1u);  // the split pass's indirect dispatch: (slots used, 1, 1)
    split_items[1] = uvec2(1u, 0u);
  }
}
