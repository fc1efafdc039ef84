#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Compute rasterizer, pass 5: one workgroup per 8 x 8 tile with entries (every tile when capturing), one thread
// per pixel. The tile's segments are
// composited front to back in depth order, a load of at most kCap entries at a time, so that a tile whose pixels
// are opaque after a few fragments orders only its nearest entries:
// - a tile with at most kSlice entries is one load;
// - a fuller tile takes a histogram of its keys over kBins bins between its nearest and farthest key and its
//   prefix sums (a subgroup scan), then loads its nearest bins holding at most kCap entries into shared memory in
//   bin order (a counting sort; a single bin fuller than kCap keeps kCap entries and counts the rest in
//   counters[3]; the bins are chosen by a parallel search over the prefix sums, not walked by one thread), and
//   loads the next bins only if its pixels are not all opaque by then;
// - the loaded entries are ranked by (depth key, a key of the segment's own screen position, so the order never
//   depends on the submission order, then position); the entries are already in bin order, so each entry is
//   ranked only among the entries of its own bin;
// - they are composited kChunk at a time in that order: each segment of the chunk marks in a 64-bit mask per
//   pixel the tile pixels it may cover (mark(): per tile row, the interval of pixel centres within half its
//   widest width plus half a pixel of its line and projecting onto it, conservative by kMaskSlack), and each
//   pixel runs the exact test below only on its marked segments, in order, instead of on all of them;
// - the tile stops when all its pixels are opaque.
// Shared memory bounds how many workgroups an SM holds, and the pass's time follows that (1 KB less made it
// 10-16 % faster on an NVIDIA H100): the entries' arrays and the histogram share one array (s_buf).
// Per pixel, every segment's analytic coverage (the pixel centre's distance to the segment against its
// interpolated width), its interpolated depth tested against the host depth (LESS_OR_EQUAL), and the fragment
// blended "under" what the pixel has through a window of kReorder fragments ordered by the pixel's own depth: the
// tile's order is each segment's depth near the tile centre, which two crossing segments can invert at a pixel;
// the window puts such near neighbours back in the pixel's order (the fragment leaving a full window is its
// nearest). A pixel stops kSettle covering fragments after its transmittance (window included) fell below
// 0.5/255: a fragment later in the tile's order can still be nearer at the pixel, and stopping at once would lose
// it where one fragment makes the pixel opaque (wide or LOD-widened strands), the window never seeing it.
// Over-full tiles (more than kSplitAt entries) are not composited by the tile's workgroup (kSplitPass 0) but by
// the split pass (kSplitPass 1): ceil(count / kSplit) workgroups per tile (the work items scan.comp listed), item
// j taking the histogram bins whose entries start in [j, j + 1) times count / items in key order, so the items
// cover the tile's depth range front to back in disjoint shares of about kSplit entries. Each composites its share
// as above (its own early termination, a window within its share) into a partial layer; the last item of the tile
// to finish merges the partials front to back into the layer. A tile of 20,000 entries then costs about what
// 1,024 do, instead of walking them all in one workgroup while the rest of the GPU idles.
// Each pixel point belongs to the segment its centre projects onto (t in [0, 1); the strand's last segment
// includes its tip), so consecutive segments of a strand never both cover it along the strand.
layout(local_size_x = 8, local_size_y = 8) in;
// Entries a tile holds in shared memory at once (kSliceCapacity in plugin/src/render/compute/state.hpp; at least
// kBins / 2, the histogram lives in half of s_buf).
layout(constant_id = 0) const uint kCap = 256u;
// A tile with at most kSlice entries is ranked whole, without the histogram (kSliceEntries in state.hpp, <= kCap).
layout(constant_id = 1) const uint kSlice = 64u;
// Fragments in the per-pixel reorder window (kReorderWindow in state.hpp); 0: blend in the tile's order.
layout(constant_id = 2) const uint kReorder = 4u;
// 1: Kajiya-Kay per fragment from the point and tangent interpolated along the segment (vertex.comp writes
// them after the drawn vertices); 0: the vertex colours interpolated (the default).
layout(constant_id = 3) const uint kPerFragment = 0u;
// 0: one workgroup per tile (over-full tiles left to the split pass); 1: one workgroup per split work item.
layout(constant_id = 4) const uint kSplitPass = 0u;
// Covering fragments a pixel still takes (into its window) once opaque (kSettleFragments in state.hpp).
layout(constant_id = 5) const uint kSettle = 4u;
#include "render/compute/raster_layout.glsl"
#include "render/compute/shade.glsl"

const uint kBins = 256u;
const uint kWindow = kReorder > 0u ? kReorder : 1u;
const float kClear = 0.5 / 255.0;  // transmittance below which a pixel is opaque
const float kEmpty = 1e31;         // depth of an empty window slot
// Slack of the coverage masks, pixels: far more than the float rounding of the exact test (1e-3 px at 4K), so a
// mask never drops a pixel the exact test covers.
const float kMaskSlack = 1.0 / 16.0;
const uint kAhead = 8u;  // entries a thread loads before using them (their latencies overlap; 8 beat 4)
const uint kChunk = 64u;  // segments composited between two barriers (a multiple of 64; 128 measured slower)

// The loaded entries: [0, kCap) their keys, [kCap, 2 kCap) their segments, [2 kCap, 3 kCap) their tie keys
// (tie_of, computed once per load); once ranked, [0, kCap) their segments in composite order (the keys are no
// longer needed). Before the tie keys are written, [2 kCap, 2 kCap + kBins) holds per bin its count (the
// histogram), then during a load the cursor of its entries (kCap >= kBins). Shared memory is this pass's
// occupancy (52-58 KB an SM on an NVIDIA H100, docs/rendering.md): each array here is counted.
shared uint s_buf[3u * kCap];
const uint kSeg = kCap, kTie = 2u * kCap, kHist = 2u * kCap;
const uint kMaxRanks = 16u;  // entries a thread ranks per load: kCap / 64 (kCap <= 1024)
shared uint s_pre[kBins + 1u];  // exclusive prefix sums of the counts (s_pre[kBins]: the tile's entries)
shared uint s_sub[64];          // per subgroup: its sum (the scan of the histogram)
shared uint s_min[3];           // the parallel searches' results, three in rotation (see next_search)
const uint kWords = kChunk / 32u;  // mask words per pixel
shared uint s_pix[kWords * 64u];  // per pixel [kWords pixel + h]: bit j of chunk segment 32 h + j that may cover it
// The chunk of segments being composited, in order: (a.xy, b.xy - a.xy), (a.z, b.z - a.z, width at a with the
// sign bit set on a strand's last segment, width change).
shared vec4 s_p0[kChunk], s_p1[kChunk];
shared uvec4 s_c[kChunk];  // colour at the start and its change along the segment, half floats
const uint kShadeSlots = kPerFragment != 0u ? kChunk : 1u;
shared vec4 s_pa[kShadeSlots], s_ta[kShadeSlots], s_dp[kShadeSlots], s_dt[kShadeSlots];  // per fragment only
shared uint s_group[kShadeSlots];
shared uint s_done, s_kmin, s_kmax, s_frags, s_hair;
shared uint s_bstart, s_bend, s_last;  // split pass: the item's bins, and whether it merges

uint bin_of(uint key, uint kmin, uint kmax) {
  return min(uint(float(key - kmin) / float(kmax - kmin + 1u) * float(kBins)), kBins - 1u);
}

// Any fixed property of the segment itself (not its index, which depends on the submission order): from its
// two screen points.
uint tie_of(vec4 a, vec4 b) { return floatBitsToUint(a.x) ^ (floatBitsToUint(b.y) * 0x9e3779b9u); }

vec3 color = vec3(0.0);
float alpha = 0.0;
float trans = 1.0;  // 1 - alpha of everything taken so far, window included
float wz[kWindow];  // the window, nearest first (kEmpty: free)
uvec2 wc[kWindow];  // premultiplied rgb and alpha, half floats

void emit(vec4 c) {
  color += (1.0 - alpha) * c.rgb;
  alpha += (1.0 - alpha) * c.a;
}

vec4 unpack(uvec2 c) { return vec4(unpackHalf2x16(c.x), unpackHalf2x16(c.y)); }

void take(float z, vec4 c) {
  trans *= 1.0 - c.a;
  if (kReorder == 0u) {
    emit(c);
    return;
  }
  if (wz[kWindow - 1u] < kEmpty) {  // full: the nearest of the window and this fragment leaves
    if (z < wz[0]) {
      emit(c);
      return;
    }
    emit(unpack(wc[0]));
    for (uint k = 0u; k + 1u < kWindow; ++k) {
      wz[k] = wz[k + 1u];
      wc[k] = wc[k + 1u];
    }
    wz[kWindow - 1u] = kEmpty;
  }
  float cz = z;
  uvec2 cc = uvec2(packHalf2x16(c.rg), packHalf2x16(c.ba));
  for (uint k = 0u; k < kWindow; ++k) {  // insertion, after equal depths (arrival order)
    if (cz < wz[k]) {
      const float tz = wz[k];
      const uvec2 tc = wc[k];
      wz[k] = cz;
      wc[k] = cc;
      cz = tz;
      cc = tc;
    }
  }
}

// The columns u in 0..7 of a tile row where lo <= a u + b <= hi may hold, as [first, last] (empty if first >
// last). |a| <= 1; below 1e-3 the value moves by less than 0.004 over the row and is tested at the row's middle
// (the bounds carry kMaskSlack, so this never drops a column).
ivec2 columns(float a, float b, float lo, float hi) {
  if (abs(a) < 1e-3) {
    const float v = a * 3.5 + b;
    return v >= lo && v <= hi ? ivec2(0, 7) : ivec2(8, -1);
  }
  const float u0 = (lo - b) / a, u1 = (hi - b) / a;
  const float ulo = clamp(min(u0, u1), -1.0, 9.0), uhi = clamp(max(u0, u1), -1.0, 9.0);
  return ivec2(max(int(ceil(ulo)), 0), min(int(floor(uhi)), 7));
}

// Marks in s_pix the tile pixels whose centre segment `slot` (from a to b, widths a.w and b.w in pixels) may
// cover: conservatively those within half its widest width plus half a pixel of its line (the exact test covers a
// pixel only where d < (w + 1) / 2, coverage() below) and whose projection falls on it (t in [0, 1]), both with
// kMaskSlack. Per tile row, each condition is linear in the column: an interval.
void mark(uint slot, vec4 a, vec4 b, vec2 origin) {
  const vec2 d = b.xy - a.xy;
  const float len = length(d);
  const vec2 e = d / len;
  const float r = 0.5 + 0.5 * max(a.w, b.w) + kMaskSlack;
  const uint word = slot >> 5u, bit = 1u << (slot & 31u);
  for (uint y = 0u; y < kTile; ++y) {
    const vec2 rel = vec2(origin.x + 0.5, origin.y + float(y) + 0.5) - a.xy;  // column 0's centre
    const ivec2 along = columns(e.x, dot(rel, e), -kMaskSlack, len + kMaskSlack);
    const ivec2 across = columns(e.y, rel.x * e.y - rel.y * e.x, -r, r);
    const int u0 = max(along.x, across.x), u1 = min(along.y, across.y);
    for (int u = u0; u <= u1; ++u) atomicOr(s_pix[kWords * (y * kTile + uint(u)) + word], bit);
  }
}

// Segment `seg` (screen points a, b and colours ca, cb) into chunk slot `slot`, its pixels marked.
void put(uint slot, uint seg, vec4 a, vec4 ca, vec4 b, vec4 cb, vec2 origin, uint n) {
  const uint si = seg % (n - 1u);
  const uint va = seg / (n - 1u) * n + si;
  const vec2 d = b.xy - a.xy;
  const vec4 dcol = cb - ca;
  s_p0[slot] = vec4(a.xy, d);
  const float wa = si + 2u >= n ? uintBitsToFloat(floatBitsToUint(a.w) | 0x80000000u) : a.w;  // last: -width
  s_p1[slot] = vec4(a.z, b.z - a.z, wa, b.w - a.w);
  s_c[slot] = uvec4(packHalf2x16(ca.rg), packHalf2x16(ca.ba), packHalf2x16(dcol.rg), packHalf2x16(dcol.ba));
  if (kPerFragment != 0u) {  // point (xyz, along) and tangent (xyz, tint) at a, and their change to b
    const uint at = 2u * (pc.params.y * n + va);
    const vec4 pa = verts[at], ta = verts[at + 1u], pb = verts[at + 2u], tb = verts[at + 3u];
    s_pa[slot] = pa;
    s_ta[slot] = ta;
    s_dp[slot] = pb - pa;
    s_dt[slot] = tb - ta;
    uint strand = seg / (n - 1u);
    if ((pc.params.z & kFlagReverse) != 0u) strand = pc.params.y - 1u - strand;
    s_group[slot] = min(guide_info[strand % dc.counts.y].x, 15u);
  }
  mark(slot, a, b, origin);
}

// Three search results in rotation: search k resets the one search k + 1 uses, which search k - 1 used and every
// thread read before the barrier that ended the phase between (every search is followed by a barrier and read).
uint search_slot = 0u;
uint begin_search() {
  const uint k = search_slot;
  search_slot = search_slot == 2u ? 0u : search_slot + 1u;
  if (gl_LocalInvocationIndex == 0u) s_min[search_slot] = 0xffffffffu;
  return k;
}

void main() {
  const uint tiles_count = pc.size.z * pc.size.w;
  uint tile, item = 0u;
  if (kSplitPass != 0u) {
    const uvec2 it = split_items[4u + gl_WorkGroupID.x];  // the dispatch is the exact number of items
    tile = it.x;
    item = it.y;
  } else if ((pc.params.z & kFlagCapture) != 0u) {
    tile = gl_WorkGroupID.y * pc.size.z + gl_WorkGroupID.x;  // every tile: a captured layer is whole
  } else {
    // The tiles with entries only (scan.comp's list, the heaviest first): the empty tiles of a frame, most of them,
    // cost no workgroup.
    const uint k = gl_WorkGroupID.y * kListRow + gl_WorkGroupID.x;
    if (k >= tiles[tile_list_at(tiles_count) + 3u]) return;
    tile = tiles[tile_list_entries_at(tiles_count) + k];
  }
  const uint slot0 = tiles[4u * tiles_count + tile];
  if (kSplitPass == 0u && slot0 != kNotSplit) return;  // uniform: the split pass composites this tile
  const uvec2 tile_xy = uvec2(tile % pc.size.z, tile / pc.size.z);
  const uint lid = gl_LocalInvocationIndex;
  const uvec2 p = tile_xy * kTile + gl_LocalInvocationID.xy;
  const bool inside = p.x < pc.size.x && p.y < pc.size.y;
  const uint pixel = p.y * pc.size.x + p.x;
  const bool capture = (pc.params.z & kFlagCapture) != 0u;

  const uint first = tiles[tiles_count + tile] + tiles[6u * tiles_count + 2u * (tile / 1024u)];  // + block offset
  const uint count = first >= pc.params.x ? 0u : min(tiles[tile], pc.params.x - first);
  const uint items = kSplitPass != 0u ? (tiles[tile] + kSplit - 1u) / kSplit : 1u;  // as scan.comp counted them
  if (count == 0u) {  // uniform over the workgroup
    // Nothing to write: the composite draws only the tiles with hair; a captured layer is whole.
    if (inside && capture) {
      capture_depth[pixel] = texelFetch(host_depth, ivec2(p), 0).r;
      image[pixel] = uvec2(0u);
    }
    return;
  }
  const float zhost = inside ? texelFetch(host_depth, ivec2(p), 0).r : 0.0;
  if (inside && item == 0u && capture) capture_depth[pixel] = zhost;
  const uint n = dc.counts.x;
  const vec2 centre = vec2(p) + 0.5;
  const vec2 origin = vec2(tile_xy * kTile);
  for (uint k = 0u; k < kWindow; ++k) {
    wz[k] = kEmpty;
    wc[k] = uvec2(0u);
  }
  uint frags = 0u;
  bool done = !inside;
  uint settle = 0u;  // covering fragments taken since the pixel became opaque

  if (lid == 0u) {
    s_done = 0u;
    s_kmin = 0xffffffffu;
    s_kmax = 0u;
    s_frags = 0u;
    s_hair = 0u;
    s_bstart = kBins;
    s_bend = kBins;
    s_min[0] = 0xffffffffu;
  }
  for (uint b = lid; b < kBins; b += 64u) s_buf[kHist + b] = 0u;
  for (uint h = 0u; h < kWords; ++h) s_pix[kWords * lid + h] = 0u;
  barrier();
  if (done) atomicAdd(s_done, 1u);
  const bool sliced = count > kSlice;
  uint kmin = 0u, kmax = 0u;
  if (sliced) {  // (a tile of at most kSlice entries loads them with their tie keys below)
    uint lmin = 0xffffffffu, lmax = 0u;
    for (uint e0 = lid; e0 < count; e0 += kAhead * 64u) {
      uint keys[kAhead];
      for (uint k = 0u; k < kAhead; ++k) keys[k] = e0 + 64u * k < count ? entries[first + e0 + 64u * k].x : 0u;
      for (uint k = 0u; k < kAhead; ++k) {
        if (e0 + 64u * k < count) {
          lmin = min(lmin, keys[k]);
          lmax = max(lmax, keys[k]);
        }
      }
    }
    lmin = subgroupMin(lmin);  // one shared atomic per subgroup, not one per entry on a single address
    lmax = subgroupMax(lmax);
    if (subgroupElect()) {
      atomicMin(s_kmin, lmin);
      atomicMax(s_kmax, lmax);
    }
    barrier();
    kmin = s_kmin;
    kmax = s_kmax;
    for (uint e0 = lid; e0 < count; e0 += kAhead * 64u) {
      uint keys[kAhead];
      for (uint k = 0u; k < kAhead; ++k) keys[k] = e0 + 64u * k < count ? entries[first + e0 + 64u * k].x : 0u;
      for (uint k = 0u; k < kAhead; ++k) {
        if (e0 + 64u * k < count) atomicAdd(s_buf[kHist + bin_of(keys[k], kmin, kmax)], 1u);
      }
    }
    if (lid == 0u && item == 0u) atomicAdd(counters[6], 1u);
    if (lid == 0u && item == 0u && kSplitPass != 0u) atomicAdd(counters[7], 1u);
    barrier();
    // Exclusive prefix sums of the histogram: each thread its 4 bins, a subgroup scan, the subgroups' sums.
    const uint h4 = kHist + 4u * lid;
    const uvec4 c = uvec4(s_buf[h4], s_buf[h4 + 1u], s_buf[h4 + 2u], s_buf[h4 + 3u]);
    const uint sum = c.x + c.y + c.z + c.w;
    uint before = subgroupExclusiveAdd(sum);
    if (gl_SubgroupInvocationID == gl_SubgroupSize - 1u) s_sub[gl_SubgroupID] = before + sum;
    barrier();
    for (uint q = 0u; q < gl_SubgroupID; ++q) before += s_sub[q];
    const uvec4 pre = uvec4(before, before + c.x, before + c.x + c.y, before + c.x + c.y + c.z);
    s_pre[4u * lid] = pre.x;
    s_pre[4u * lid + 1u] = pre.y;
    s_pre[4u * lid + 2u] = pre.z;
    s_pre[4u * lid + 3u] = pre.w;
    if (lid == 63u) s_pre[kBins] = before + sum;
    if (kSplitPass != 0u) {
      // Bin b belongs to item min(items - 1, (entries in the bins before b) / share).
      const uint share = max((count + items - 1u) / items, 1u);
      for (uint k = 0u; k < 4u; ++k) {
        const uint owner = min(items - 1u, pre[k] / share);
        if (owner >= item) atomicMin(s_bstart, 4u * lid + k);
        if (owner > item) atomicMin(s_bend, 4u * lid + k);
      }
    }
    barrier();
  }
  uint wend = kBins;  // the bins this workgroup composites: [w0, wend)
  uint w0 = 0u;       // first bin in shared memory
  if (kSplitPass != 0u) {
    w0 = s_bstart;
    wend = s_bend;
  }
  bool stop = false;
  while (!stop && w0 < wend) {
    uint w1 = kBins;
    uint base = 0u;  // entries in the bins before w0
    if (sliced) {
      // Bins [w0, w1) into shared memory: at most kCap entries (at least one bin with entries): w1 is the first
      // bin that would overflow them after some entries. Each bin's cursor starts at its entries before it.
      const uint sk = begin_search();
      base = s_pre[w0];
      for (uint b = 4u * lid; b < 4u * lid + 4u; ++b) {
        if (b < w0 || b >= wend) continue;
        const uint before = s_pre[b] - base;
        if (before != 0u && s_pre[b + 1u] - base > kCap) atomicMin(s_min[sk], b);
        s_buf[kHist + b] = before;
      }
      barrier();
      w1 = min(s_min[sk], wend);
      for (uint e0 = lid; e0 < count; e0 += kAhead * 64u) {
        uvec2 ahead[kAhead];
        for (uint k = 0u; k < kAhead; ++k) {
          ahead[k] = e0 + 64u * k < count ? entries[first + e0 + 64u * k] : uvec2(0xffffffffu, 0u);
        }
        for (uint k = 0u; k < kAhead; ++k) {
          const uvec2 entry = ahead[k];
          const uint bin = e0 + 64u * k < count ? bin_of(entry.x, kmin, kmax) : kBins;
          if (bin >= w0 && bin < w1) {
            const uint at = atomicAdd(s_buf[kHist + bin], 1u);
            if (at < kCap) {
              s_buf[at] = entry.x;
              s_buf[kSeg + at] = entry.y;
            } else {
              atomicAdd(counters[3], 1u);  // one bin fuller than kCap
            }
          }
        }
      }
      barrier();
    }
    // The loaded entries in composite order: by bin (they are stored so), then within their bin by key, tie key
    // and position (a total order independent of the submission order). Each entry's tie key first (from its
    // screen points, kept for the chunk when all fit in one), then its rank among its bin's entries.
    const uint m = sliced ? min(s_pre[w1] - base, kCap) : count;
    const bool one = m <= 64u;  // uniform
    uint seg = 0u;
    vec4 a = vec4(0.0), ca = vec4(0.0), b = vec4(0.0), cb = vec4(0.0);
    for (uint i = lid; i < m; i += 64u) {
      if (sliced) {
        seg = s_buf[kSeg + i];
      } else {
        const uvec2 entry = entries[first + i];
        s_buf[i] = entry.x;
        s_buf[kSeg + i] = entry.y;
        seg = entry.y;
      }
      const uint va = seg / (n - 1u) * n + seg % (n - 1u);
      a = verts[2u * va];
      b = verts[2u * va + 2u];
      if (one) {
        ca = verts[2u * va + 1u];
        cb = verts[2u * va + 3u];
      }
      s_buf[kTie + i] = tie_of(a, b);
    }
    barrier();
    uint ranks[kMaxRanks];
    for (uint i = lid; i < m; i += 64u) {
      const uint ki = s_buf[i], ti = s_buf[kTie + i];
      uint lo = 0u, hi = m;
      if (sliced) {
        const uint bin = bin_of(ki, kmin, kmax);
        lo = min(s_pre[bin] - base, kCap);
        hi = min(s_pre[bin + 1u] - base, kCap);
      }
      uint r = lo;
      for (uint j = lo; j < hi; ++j) {
        const uint kj = s_buf[j];
        if (kj < ki || (kj == ki && j != i && (s_buf[kTie + j] < ti || (s_buf[kTie + j] == ti && j < i)))) ++r;
      }
      if (one) {
        put(r, seg, a, ca, b, cb, origin, n);
      } else {
        ranks[(i - lid) / 64u] = r;
      }
    }
    barrier();
    if (!one) {  // the segments in composite order, over the keys every rank above has read
      for (uint q = 0u; q < kCap / 64u; ++q) {
        const uint i = lid + 64u * q;
        const uint s = i < m ? s_buf[kSeg + i] : 0u;
        if (i < m) s_buf[ranks[q]] = s;
      }
      barrier();
    }
    {
      // Front-to-back compositing, kChunk segments at a time: each segment in shared memory (in the form the
      // per-pixel test needs) has marked the pixels it may cover; every pixel runs the exact test on its marked
      // segments only, in order.
      for (uint base = 0u; base < m; base += kChunk) {
        if (!one) {
          for (uint slot = lid; slot < kChunk && base + slot < m; slot += 64u) {
            seg = s_buf[base + slot];
            const uint va = seg / (n - 1u) * n + seg % (n - 1u);
            put(slot, seg, verts[2u * va], verts[2u * va + 1u], verts[2u * va + 2u], verts[2u * va + 3u], origin, n);
          }
          barrier();
        }
        for (uint h = 0u; h < kWords && !done; ++h) {
          uint bits = s_pix[kWords * lid + h];
          while (bits != 0u) {
            const uint j = 32u * h + uint(findLSB(bits));
            bits &= bits - 1u;
            const vec4 p0 = s_p0[j];
            const vec2 rel = centre - p0.xy;
            const vec4 p1 = s_p1[j];
            const float t = dot(rel, p0.zw) * (1.0 / dot(p0.zw, p0.zw));
            const bool last = (floatBitsToUint(p1.z) & 0x80000000u) != 0u;  // the strand's tip belongs to it
            if (t < 0.0 || t > 1.0 || (t == 1.0 && !last)) continue;
            const float cov = coverage(length(rel - t * p0.zw), abs(p1.z) + t * p1.w);
            if (cov <= 0.0) continue;
            const float z = p1.x + t * p1.y;
            if (z > zhost) continue;  // behind the host's opaque surface
            const uvec4 cp = s_c[j];
            vec4 c = unpack(cp.xy) + t * unpack(cp.zw);
            if (kPerFragment != 0u) {
              const vec4 pt = s_pa[j] + t * s_dp[j], tt = s_ta[j] + t * s_dt[j];
              c.rgb = shade_hair(pt.xyz, tt.xyz, pt.w, dc.materials[s_group[j]], tt.w);
            }
            const float fa = cov * c.a;
            take(z, vec4(fa * c.rgb, fa));
            ++frags;
            if (trans <= kClear && settle++ >= kSettle) {
              done = true;
              atomicAdd(s_done, 1u);
              break;
            }
          }
        }
        for (uint h = 0u; h < kWords; ++h) s_pix[kWords * lid + h] = 0u;  // for the next chunk's marks
        barrier();  // the chunk is read; s_done is final until the next chunk's compositing
        stop = s_done == 64u;
        if (stop) break;
      }
    }
    w0 = w1;
  }
  for (uint k = 0u; k < kWindow; ++k) {
    if (wz[k] < kEmpty) emit(unpack(wc[k]));
  }
  atomicAdd(s_frags, frags);
  if (kSplitPass == 0u) {
    if (inside) image[pixel] = uvec2(packHalf2x16(color.rg), packHalf2x16(vec2(color.b, alpha)));
    if (alpha > 0.0) atomicAdd(s_hair, 1u);
  } else {
    // This item's share into its partial layer; the tile's last item to finish merges all of them in order.
    partials[(slot0 + item) * 64u + lid] = uvec2(packHalf2x16(color.rg), packHalf2x16(vec2(color.b, alpha)));
    memoryBarrierBuffer();
    barrier();
    if (lid == 0u) s_last = atomicAdd(tiles[5u * tiles_count + tile], 1u) == items - 1u ? 1u : 0u;
    barrier();
    if (s_last != 0u) {  // uniform
      memoryBarrierBuffer();
      color = vec3(0.0);
      alpha = 0.0;
      for (uint j = 0u; j < items; ++j) emit(unpack(partials[(slot0 + j) * 64u + lid]));
      if (inside) image[pixel] = uvec2(packHalf2x16(color.rg), packHalf2x16(vec2(color.b, alpha)));
      if (alpha > 0.0) atomicAdd(s_hair, 1u);
    }
  }
  barrier();
  if (lid == 0u) {
    atomicAdd(counters[4], s_frags);
    atomicAdd(counters[5], s_hair);
    if (s_hair > 0u) {  // this tile's quad for the composite's indirect draw (after the layer's pixels)
      const uint at = pc.size.x * pc.size.y;
      const uint quad = atomicAdd(image[at].x, 6u) / 6u;  // VkDrawIndirectCommand.vertexCount
      image[at + 2u + quad] = tile_xy;
    }
  }
}
