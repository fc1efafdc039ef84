#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Compute rasterizer, pass 3: exclusive prefix sum of the tiles' segment counts -> first entry and scatter cursor
// per tile, and the work items of the over-full tiles, in two dispatches:
// - kTop 0, one workgroup of 1024 threads per block of 1024 tiles (1080p: 32 blocks, all at once): a thread per
//   tile (coalesced), a subgroup scan and a scan of the subgroups' sums give each tile's offset within its block
//   ([T + t] and [2T + t]); the block's totals (entries, split work items) go to [6T + 2b], and its tiles with
//   entries are counted per weight bucket (raster_layout.glsl);
// - kTop 1, one workgroup: the exclusive scan of the blocks' totals replaces them by the blocks' offsets, which the
//   scatter (cursor) and fine (first entry) passes add to the tile's own, and the scan of the buckets' counts gives
//   each bucket its place in the fine pass's list, heaviest first (the scatter pass lists the tiles there). A single
//   workgroup walking every tile in series measured 0.061 ms at 1080p on the H100, where the blocks run side by
//   side.
// A tile with more than kSplitAt entries is split into ceil(count / kSplit) work items (fine.comp composites each
// item's share of the tile's depth range in its own workgroup and the last one to finish merges them): the top
// pass numbers their slots in tile order, for the blocks that hold any (uniform: none in most frames), writes each
// such tile's items (tile, index) into the split list, and the indirect dispatch size of the split pass is the
// number of slots used. A tile whose items would not fit in the slots (pc.split.x) stays whole (slower, never wrong).
layout(local_size_x = 1024) in;
layout(constant_id = 0) const uint kTop = 0u;
#include "render/compute/raster_layout.glsl"

shared uvec2 s_sub[1024];  // per subgroup: its sums, then the sums of the subgroups before it
shared uvec2 s_total;      // the workgroup's totals
shared uint s_used;        // split slots used
shared uint s_hist[kBuckets];  // this block's tiles with entries per weight bucket
shared uint s_over;            // this block's tiles over kSplitFewAt entries

// Work items of a tile of v entries split above `at` entries.
uint items_of(uint v, uint at) { return v > at ? (v + kSplit - 1u) / kSplit : 0u; }
const uint kFewFlag = 0x80000000u;  // a block's split-item word: the block has a tile over kSplitFewAt entries

// Exclusive scan of x over the workgroup (every invocation calls it); s_total gets the sum.
uvec2 workgroup_exclusive(uvec2 x) {
  const uvec2 inclusive = subgroupInclusiveAdd(x);
  if (gl_SubgroupInvocationID == gl_SubgroupSize - 1u) s_sub[gl_SubgroupID] = inclusive;
  barrier();
  if (gl_SubgroupID == 0u) {
    uvec2 run = uvec2(0u);
    for (uint w0 = 0u; w0 < gl_NumSubgroups; w0 += gl_SubgroupSize) {
      const uint w = w0 + gl_SubgroupInvocationID;
      const uvec2 y = w < gl_NumSubgroups ? s_sub[w] : uvec2(0u);
      const uvec2 before = subgroupExclusiveAdd(y);
      if (w < gl_NumSubgroups) s_sub[w] = run + before;
      run += subgroupAdd(y);
    }
    if (subgroupElect()) s_total = run;
  }
  barrier();
  const uvec2 result = s_sub[gl_SubgroupID] + inclusive - x;
  barrier();  // s_sub and s_total may be rewritten by the next call
  return result;
}

void main() {
  const uint tiles_count = pc.size.z * pc.size.w;
  const uint blocks = (tiles_count + 1023u) / 1024u;
  const uint i = gl_LocalInvocationIndex;
  const uint top = 6u * tiles_count;  // the blocks' totals, then offsets: (entries, split slots) per block
  if (kTop == 0u) {
    const uint b = gl_WorkGroupID.x;
    const uint t = b * 1024u + i;
    const uint v = t < tiles_count ? tiles[t] : 0u;
    const uvec2 offset = workgroup_exclusive(uvec2(v, items_of(v, kSplitAt)));
    if (t < tiles_count) {
      tiles[tiles_count + t] = offset.x;
      tiles[2u * tiles_count + t] = offset.x;
      tiles[4u * tiles_count + t] = kNotSplit;  // the top pass marks the split tiles
      tiles[5u * tiles_count + t] = 0u;         // items of the tile finished (fine.comp)
    }
    // The tiles with entries, for the fine pass, counted per weight bucket (the top pass turns the counts into
    // the buckets' places in the list, the scatter pass lists the tiles); and the tiles over kSplitFewAt entries,
    // counted for the call (the top pass splits them if they are few) and flagged per block (the blocks it then
    // walks).
    if (i < kBuckets) s_hist[i] = 0u;
    if (i == 0u) s_over = 0u;
    barrier();
    if (t < tiles_count && v > 0u) atomicAdd(s_hist[weight_bucket(v)], 1u);
    const uint over = subgroupAdd(t < tiles_count && v > kSplitFewAt ? 1u : 0u);
    if (subgroupElect() && over > 0u) atomicAdd(s_over, over);
    barrier();
    if (i < kBuckets && s_hist[i] > 0u) atomicAdd(tiles[tile_list_buckets_at(tiles_count) + i], s_hist[i]);
    if (i == 0u) {
      // s_total is workgroup_exclusive's above: nothing in this pass has called it since.
      tiles[top + 2u * b] = s_total.x;
      tiles[top + 2u * b + 1u] = s_total.y | (s_over > 0u ? kFewFlag : 0u);
      if (s_over > 0u) atomicAdd(tiles[tile_list_at(tiles_count) + 4u], s_over);
    }
    return;
  }
  if (i == 0u) s_used = 0u;
  uvec2 carry = uvec2(0u);
  for (uint b0 = 0u; b0 < blocks; b0 += 1024u) {  // uniform
    const uint b = b0 + i;
    const uint items = b < blocks ? tiles[top + 2u * b + 1u] : 0u;  // with the block's kFewFlag
    const uvec2 total = b < blocks ? uvec2(tiles[top + 2u * b], items & ~kFewFlag) : uvec2(0u);
    const uvec2 offset = carry + workgroup_exclusive(total);
    carry += s_total;  // s_total stays until the next call's first barrier
    if (b < blocks) {
      tiles[top + 2u * b] = offset.x;
      tiles[top + 2u * b + 1u] = offset.y | (items & kFewFlag);
    }
  }
  // The weight buckets' places in the fine pass's list (the heaviest first): the scatter pass's cursors.
  const uint buckets = tile_list_buckets_at(tiles_count);
  const uint in_bucket = i < kBuckets ? tiles[buckets + i] : 0u;
  const uint place = workgroup_exclusive(uvec2(in_bucket, 0u)).x;
  const uint all = s_total.x;  // s_total stays until the next call's first barrier
  if (i < kBuckets) tiles[buckets + kBuckets + i] = place;
  memoryBarrierBuffer();
  barrier();
  // Few tiles over kSplitFewAt entries (uniform): they would end the fine pass alone, so they are split too; the
  // slots are then numbered over the flagged blocks in order (a block without such a tile has none to split).
  // Many (a dense groom): the GPU is full of tiles anyway, and splitting them costs more than it saves, since the
  // shares of a nearly opaque tile composite what its nearer shares hide (measured on an NVIDIA H100: the head
  // sample 0.96 -> 0.78 ms, 100,000 x 32 strands with 3,251 such tiles 3.69 -> 4.91 ms).
  const uint over_few = tiles[tile_list_at(tiles_count) + 4u];
  const bool few = over_few > 0u && over_few <= kSplitFew && (pc.params.z & kFlagSplitDense) == 0u;
  if (few) {
    uint next_slot = 0u;
    for (uint b = 0u; b < blocks; ++b) {
      if ((tiles[top + 2u * b + 1u] & kFewFlag) == 0u) continue;  // uniform
      const uint t = b * 1024u + i;
      const uint k = t < tiles_count ? items_of(tiles[t], kSplitFewAt) : 0u;
      const uint slot = next_slot + workgroup_exclusive(uvec2(0u, k)).y;
      next_slot += s_total.y;  // s_total stays until the next call's first barrier
      if (k > 0u && slot + k <= pc.split.x) {
        tiles[4u * tiles_count + t] = slot;
        for (uint j = 0u; j < k; ++j) split_items[4u + slot + j] = uvec2(t, j);
        atomicMax(s_used, slot + k);
      }
    }
  } else if (carry.y > 0u) {  // uniform: some tile is over-full; number the split slots of the blocks that hold any
    for (uint b = 0u; b < blocks; ++b) {
      const uint first_slot = tiles[top + 2u * b + 1u] & ~kFewFlag;
      const uint end_slot = b + 1u < blocks ? tiles[top + 2u * b + 3u] & ~kFewFlag : carry.y;
      if (first_slot == end_slot) continue;  // uniform
      const uint t = b * 1024u + i;
      const uint k = t < tiles_count ? items_of(tiles[t], kSplitAt) : 0u;
      const uint slot = first_slot + workgroup_exclusive(uvec2(0u, k)).y;
      if (k > 0u && slot + k <= pc.split.x) {
        tiles[4u * tiles_count + t] = slot;
        for (uint j = 0u; j < k; ++j) split_items[4u + slot + j] = uvec2(t, j);
        atomicMax(s_used, slot + k);
      }
    }
  }
  barrier();
  if (i == 0u) {
    if (carry.x > pc.params.x) counters[1] = carry.x - pc.params.x;  // entries that did not fit
    // The split pass's indirect dispatches, (slots used, 1, 1): few split tiles before the fine pass (they are the
    // frame's heaviest work and would end it if started last: Ratboy + 4 follows 0.48 -> 0.53 ms with its one tile
    // over 2,048 entries split after it), the many over-full tiles of a dense groom after it (0.13 ms faster there
    // on 100,000 x 32 strands, whose split items would hold the SMs' shared memory first).
    split_items[0] = uvec2(few ? 0u : s_used, 1u);
    split_items[1] = uvec2(1u, 0u);
    split_items[2] = uvec2(few ? s_used : 0u, 1u);
    split_items[3] = uvec2(1u, 0u);
    const uint list = tile_list_at(tiles_count);  // the fine pass's dispatch: rows of kListRow
    tiles[list + 3u] = all;
    tiles[list] = min(all, kListRow);
    tiles[list + 1u] = (all + kListRow - 1u) / kListRow;
    tiles[list + 2u] = 1u;
  }
}
