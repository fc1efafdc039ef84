#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Compute rasterizer, pass 5: one workgroup per 8 x 8 tile, one thread per pixel. The tile's segments are
// composited front to back in depth order, a small slice at a time, so that a tile whose pixels are opaque after
// a few fragments orders only its nearest entries:
// - a tile with at most kSlice entries is one slice;
// - a fuller tile takes a histogram of its keys over kBins bins between its nearest and farthest key, then
//   loads its nearest bins holding at most kCap entries into shared memory in bin order (a counting sort; a
//   single bin fuller than kCap keeps kCap entries and counts the rest in counters[3]), and reloads the next
//   bins only if its pixels are not all opaque by then;
// - a slice is consecutive bins holding at most kSlice entries (or one fuller bin), ranked by (depth key, a key
//   of the segment's own screen position, so the order never depends on the submission order, then position)
//   and composited 64 at a time; the tile stops when all its pixels are opaque.
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
// Entries a tile holds in shared memory at once (kSliceCapacity in plugin/src/render/compute/state.hpp).
layout(constant_id = 0) const uint kCap = 256u;
// Entries per slice (kSliceEntries in state.hpp).
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

shared uint s_key[kCap];
shared uint s_seg[kCap];
shared uint s_hist[kBins];  // per bin: its count; for the bins in shared memory, the end of their entries
shared vec4 s_p0[64], s_p1[64];  // the chunk of segments being composited, in order
shared uvec4 s_c[64];            // colour at the start and its change along the segment, half floats
shared vec2 s_p2[64];
const uint kShadeSlots = kPerFragment != 0u ? 64u : 1u;
shared vec4 s_pa[kShadeSlots], s_ta[kShadeSlots], s_dp[kShadeSlots], s_dt[kShadeSlots];  // per fragment only
shared uint s_group[kShadeSlots];
shared uint s_count, s_done, s_kmin, s_kmax, s_w1, s_b1, s_frags, s_hair;
shared uint s_part[64], s_bstart, s_bend, s_last;  // split pass: the item's bins, and whether it merges

uint bin_of(uint key, uint kmin, uint kmax) {
  return min(uint(float(key - kmin) / float(kmax - kmin + 1u) * float(kBins)), kBins - 1u);
}

// Any fixed property of the segment itself (not its index, which depends on the submission order).
uint tie_of(uint seg, uint n) {
  const uint va = seg / (n - 1u) * n + seg % (n - 1u);
  return floatBitsToUint(verts[2u * va].x) ^ (floatBitsToUint(verts[2u * va + 2u].y) * 0x9e3779b9u);
}

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

void main() {
  const uint tiles_count = pc.size.z * pc.size.w;
  uint tile, item = 0u;
  if (kSplitPass != 0u) {
    if (gl_WorkGroupID.x >= split_items[0].x) return;
    const uvec2 it = split_items[2u + gl_WorkGroupID.x];
    tile = it.x;
    item = it.y;
  } else {
    tile = gl_WorkGroupID.y * pc.size.z + gl_WorkGroupID.x;
  }
  const uint slot0 = tiles[4u * tiles_count + tile];
  if (kSplitPass == 0u && slot0 != kNotSplit) return;  // uniform: the split pass composites this tile
  const uvec2 tile_xy = uvec2(tile % pc.size.z, tile / pc.size.z);
  const uint lid = gl_LocalInvocationIndex;
  const uvec2 p = tile_xy * kTile + gl_LocalInvocationID.xy;
  const bool inside = p.x < pc.size.x && p.y < pc.size.y;
  const uint pixel = p.y * pc.size.x + p.x;
  const bool capture = (pc.params.z & kFlagCapture) != 0u;

  const uint first = tiles[tiles_count + tile];
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
  }
  for (uint b = lid; b < kBins; b += 64u) s_hist[b] = 0u;
  barrier();
  if (done) atomicAdd(s_done, 1u);
  const bool sliced = count > kSlice;
  uint kmin = 0u, kmax = 0u;
  if (!sliced) {
    for (uint e = lid; e < count; e += 64u) {
      const uvec2 entry = entries[first + e];
      s_key[e] = entry.x;
      s_seg[e] = entry.y;
    }
  } else {
    uint lmin = 0xffffffffu, lmax = 0u;
    for (uint e = lid; e < count; e += 64u) {
      const uint key = entries[first + e].x;
      lmin = min(lmin, key);
      lmax = max(lmax, key);
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
    for (uint e = lid; e < count; e += 64u) atomicAdd(s_hist[bin_of(entries[first + e].x, kmin, kmax)], 1u);
    if (lid == 0u && item == 0u) atomicAdd(counters[6], 1u);
    if (lid == 0u && item == 0u && kSplitPass != 0u) atomicAdd(counters[7], 1u);
  }
  barrier();
  uint wend = kBins;  // the bins this workgroup composites: [w0, wend)
  uint w0 = 0u;       // first bin in shared memory
  if (kSplitPass != 0u) {
    // Bin b belongs to item min(items - 1, (entries in the bins before b) / share): each thread sums 4 bins, the
    // entries before its bins are the sums of the threads before it.
    const uint share = (count + items - 1u) / items;
    s_part[lid] = s_hist[4u * lid] + s_hist[4u * lid + 1u] + s_hist[4u * lid + 2u] + s_hist[4u * lid + 3u];
    if (lid == 0u) {
      s_bstart = kBins;
      s_bend = kBins;
    }
    barrier();
    uint before = 0u;
    for (uint q = 0u; q < lid; ++q) before += s_part[q];
    for (uint b = 4u * lid; b < 4u * lid + 4u; ++b) {
      const uint owner = min(items - 1u, before / max(share, 1u));
      if (owner >= item) atomicMin(s_bstart, b);
      if (owner > item) atomicMin(s_bend, b);
      before += s_hist[b];
    }
    barrier();
    w0 = s_bstart;
    wend = s_bend;
  }
  bool stop = false;
  while (!stop && w0 < wend) {
    if (sliced) {
      // Bins [w0, w1) into shared memory: at most kCap entries (at least one bin with entries); their counts
      // become their starts, then (after the scatter) their ends.
      if (lid == 0u) {
        uint b = w0, acc = 0u;
        while (b < wend) {
          const uint c = s_hist[b];
          if (acc != 0u && acc + c > kCap) break;
          s_hist[b] = acc;
          acc += c;
          ++b;
        }
        s_w1 = b;
      }
      barrier();
      const uint w1 = s_w1;
      for (uint e = lid; e < count; e += 64u) {
        const uvec2 entry = entries[first + e];
        const uint bin = bin_of(entry.x, kmin, kmax);
        if (bin >= w0 && bin < w1) {
          const uint at = atomicAdd(s_hist[bin], 1u);
          if (at < kCap) {
            s_key[at] = entry.x;
            s_seg[at] = entry.y;
          } else {
            atomicAdd(counters[3], 1u);  // one bin fuller than kCap
          }
        }
      }
      barrier();
      if (lid == 0u) s_hist[w1 - 1u] = min(s_hist[w1 - 1u], kCap);
    }
    const uint w1 = sliced ? s_w1 : kBins;
    uint b0 = w0;
    while (b0 < w1) {
      // The next slice: bins [b0, b1) with at most kSlice entries (at least one bin).
      if (lid == 0u) {
        uint b = sliced ? b0 : w1;
        uint acc = 0u;
        while (b < w1) {
          const uint c = s_hist[b] - (b == w0 ? 0u : s_hist[b - 1u]);
          if (acc != 0u && acc + c > kSlice) break;
          acc += c;
          ++b;
        }
        s_b1 = b;
      }
      barrier();
      const uint b1 = s_b1;
      const uint o0 = !sliced || b0 == w0 ? 0u : s_hist[b0 - 1u];
      const uint m = (sliced ? s_hist[b1 - 1u] : count) - o0;
      // Front-to-back compositing of the slice, 64 segments at a time: each thread ranks its entries (the ones
      // before it by key, tie key and position) and puts those of this chunk in shared memory in order (in the
      // form the per-pixel test needs), then every pixel walks them.
      for (uint base = 0u; base < m; base += 64u) {
        for (uint i = lid; i < m; i += 64u) {
          const uint ki = s_key[o0 + i], seg = s_seg[o0 + i];
          uint ti = 0xffffffffu;
          uint r = 0u;
          for (uint j = 0u; j < m; ++j) {
            const uint kj = s_key[o0 + j];
            if (kj < ki) {
              ++r;
            } else if (kj == ki && j != i) {
              if (ti == 0xffffffffu) ti = tie_of(seg, n);
              const uint tj = tie_of(s_seg[o0 + j], n);
              if (tj < ti || (tj == ti && j < i)) ++r;
            }
          }
          const uint slot = r - base;
          if (slot >= 64u) continue;
          const uint si = seg % (n - 1u);
          const uint va = seg / (n - 1u) * n + si;
          const vec4 a = verts[2u * va], ca = verts[2u * va + 1u];
          const vec4 b = verts[2u * va + 2u], cb = verts[2u * va + 3u];
          const vec2 d = b.xy - a.xy;
          const vec4 dcol = cb - ca;
          s_p0[slot] = vec4(a.xy, d);
          s_p1[slot] = vec4(a.z, b.z - a.z, a.w, b.w - a.w);
          s_p2[slot] = vec2(1.0 / dot(d, d), si + 2u >= n ? 1.0 : 0.0);
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
        }
        barrier();
        if (!done) {
          const uint chunk = min(64u, m - base);
          for (uint j = 0u; j < chunk; ++j) {
            const vec4 p0 = s_p0[j];
            const vec2 rel = centre - p0.xy;
            const vec2 p2 = s_p2[j];
            const float t = dot(rel, p0.zw) * p2.x;
            if (t < 0.0 || t > 1.0 || (t == 1.0 && p2.y == 0.0)) continue;
            const vec4 p1 = s_p1[j];
            const float cov = coverage(length(rel - t * p0.zw), p1.z + t * p1.w);
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
        barrier();  // the chunk is read; s_done is final until the next chunk's compositing
        stop = s_done == 64u;
        if (stop) break;
      }
      if (stop) break;
      b0 = b1;
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
