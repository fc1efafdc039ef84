#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Compute rasterizer, pass 5: one workgroup per 8 x 8 tile, one thread per pixel. The tile's segments are
// composited front to back in depth order:
// - a tile with at most kCap segments sorts them all in shared memory (bitonic sort on the depth key);
// - a fuller tile is cut into depth slices: a histogram of its keys over kBins bins between its nearest and
//   farthest key, then consecutive bins grouped into slices of at most kCap segments, each loaded, sorted and
//   composited in turn (ties in depth broken by the segment's own screen position, so the order never depends
//   on the submission order) (a single bin fuller than kCap keeps its kCap nearest-loaded entries and counts the rest
//   in counters[3]);
// - every pixel evaluates each segment's analytic coverage (the pixel centre's distance to the segment against
//   its interpolated width), tests the fragment's interpolated depth against the host depth (LESS_OR_EQUAL), and
//   blends premultiplied colour "under" what it has; a pixel stops at alpha >= 1 - 0.5/255, the tile (and the
//   remaining slices) when all its pixels have.
// Each pixel point belongs to the segment its centre projects onto (t in [0, 1); the strand's last segment
// includes its tip), so consecutive segments of a strand never both cover it along the strand.
layout(local_size_x = 8, local_size_y = 8) in;
// Segments sorted at once per tile slice (kSliceCapacity in plugin/src/render/compute/state.hpp, a power of two).
layout(constant_id = 0) const uint kCap = 1024u;
#include "render/compute/raster_layout.glsl"

const uint kBins = 256u;
const float kOpaque = 1.0 - 0.5 / 255.0;

shared uint s_key[kCap];
shared uint s_seg[kCap];
shared uint s_tie[kCap];  // second sort key: segments with the same depth key keep an order of their own
shared uint s_hist[kBins];
shared vec4 s_p0[64], s_p1[64], s_c0[64], s_c1[64];  // the chunk of segments being composited
shared vec2 s_p2[64];
shared uint s_count, s_done, s_kmin, s_kmax, s_b1, s_frags, s_hair;

uint bin_of(uint key, uint kmin, uint kmax) {
  return min(uint(float(key - kmin) / float(kmax - kmin + 1u) * float(kBins)), kBins - 1u);
}

void main() {
  const uint tiles_count = pc.size.z * pc.size.w;
  const uint tile = gl_WorkGroupID.y * pc.size.z + gl_WorkGroupID.x;
  const uint lid = gl_LocalInvocationIndex;
  const uvec2 p = gl_GlobalInvocationID.xy;
  const bool inside = p.x < pc.size.x && p.y < pc.size.y;
  const uint pixel = p.y * pc.size.x + p.x;
  const float zhost = inside ? texelFetch(host_depth, ivec2(p), 0).r : 0.0;
  if (inside && (pc.params.z & kFlagCapture) != 0u) capture_depth[pixel] = zhost;

  const uint first = tiles[tiles_count + tile];
  const uint count = first >= pc.params.x ? 0u : min(tiles[tile], pc.params.x - first);
  if (count == 0u) {  // uniform over the workgroup
    if (inside) image[pixel] = uvec2(0u);
    return;
  }
  const uint n = dc.counts.x;
  const vec2 centre = vec2(p) + 0.5;
  vec3 color = vec3(0.0);
  float alpha = 0.0;
  uint frags = 0u;
  bool done = !inside;

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
  const bool sliced = count > kCap;
  uint kmin = 0u, kmax = 0u;
  if (sliced) {
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
    if (lid == 0u) atomicAdd(counters[6], 1u);
  }
  barrier();

  uint b0 = 0u;
  while (b0 < kBins) {
    // The next slice: bins [b0, b1) with at most kCap entries (at least one bin).
    if (lid == 0u) {
      uint b = b0, acc = 0u;
      if (!sliced) {
        b = kBins;
      } else {
        while (b < kBins && (acc == 0u || acc + s_hist[b] <= kCap)) acc += s_hist[b++];
      }
      s_b1 = b;
      s_count = 0u;
    }
    barrier();
    const uint b1 = s_b1;
    for (uint e = lid; e < count; e += 64u) {
      const uvec2 entry = entries[first + e];
      bool take = true;
      if (sliced) {
        const uint bin = bin_of(entry.x, kmin, kmax);
        take = bin >= b0 && bin < b1;
      }
      if (take) {
        const uint at = atomicAdd(s_count, 1u);
        if (at < kCap) {
          s_key[at] = entry.x;
          s_seg[at] = entry.y;
          // Any fixed property of the segment itself (not its index, which depends on the submission order).
          const uint va = entry.y / (n - 1u) * n + entry.y % (n - 1u);
          s_tie[at] = floatBitsToUint(verts[2u * va].x) ^ (floatBitsToUint(verts[2u * va + 2u].y) * 0x9e3779b9u);
        }
      }
    }
    barrier();
    const uint loaded = s_count;
    const uint m = min(loaded, kCap);
    if (lid == 0u && loaded > kCap) atomicAdd(counters[3], loaded - kCap);
    uint size = 1u;
    while (size < m) size <<= 1u;
    for (uint e = m + lid; e < size; e += 64u) {
    s_key[e] = 0xffffffffu;
    s_tie[e] = 0xffffffffu;
  }
    barrier();
    // Bitonic sort of [0, size) by key, ascending (nearest first).
    for (uint k = 2u; k <= size; k <<= 1u) {
      for (uint j = k >> 1u; j > 0u; j >>= 1u) {
        for (uint i = lid; i < size; i += 64u) {
          const uint l = i ^ j;
          if (l > i) {
            const uint ki = s_key[i], kl = s_key[l], ti = s_tie[i], tl = s_tie[l];
            const bool greater = ki > kl || (ki == kl && ti > tl);
            if (greater == ((i & k) == 0u)) {
              s_key[i] = kl;
              s_key[l] = ki;
              s_tie[i] = tl;
              s_tie[l] = ti;
              const uint si = s_seg[i];
              s_seg[i] = s_seg[l];
              s_seg[l] = si;
            }
          }
        }
        barrier();
      }
    }
    // Front-to-back compositing of the slice, 64 segments at a time: each thread loads one segment into shared
    // memory (already in the form the per-pixel test needs), then every pixel walks the 64 in order.
    for (uint base = 0u; base < m; base += 64u) {
      barrier();
      const bool all_done = s_done == 64u;
      barrier();
      if (all_done) break;
      if (base + lid < m) {
        const uint seg = s_seg[base + lid];
        const uint i = seg % (n - 1u);
        const uint va = seg / (n - 1u) * n + i;
        const vec4 a = verts[2u * va], ca = verts[2u * va + 1u];
        const vec4 b = verts[2u * va + 2u], cb = verts[2u * va + 3u];
        const vec2 d = b.xy - a.xy;
        s_p0[lid] = vec4(a.xy, d);
        s_p1[lid] = vec4(a.z, b.z - a.z, a.w, b.w - a.w);
        s_p2[lid] = vec2(1.0 / dot(d, d), i + 2u >= n ? 1.0 : 0.0);
        s_c0[lid] = ca;
        s_c1[lid] = cb - ca;
      }
      barrier();
      if (done) continue;
      const uint chunk = min(64u, m - base);
      for (uint j = 0u; j < chunk; ++j) {
        const vec4 p0 = s_p0[j];
        const vec2 rel = centre - p0.xy;
        const float t = dot(rel, p0.zw) * s_p2[j].x;
        if (t < 0.0 || t > 1.0 || (t == 1.0 && s_p2[j].y == 0.0)) continue;
        const vec4 p1 = s_p1[j];
        const float cov = coverage(length(rel - t * p0.zw), p1.z + t * p1.w);
        if (cov <= 0.0) continue;
        if (p1.x + t * p1.y > zhost) continue;  // behind the host's opaque surface
        const vec4 c = s_c0[j] + t * s_c1[j];
        const float fa = cov * c.a;
        color += (1.0 - alpha) * fa * c.rgb;
        alpha += (1.0 - alpha) * fa;
        ++frags;
        if (alpha >= kOpaque) {
          done = true;
          atomicAdd(s_done, 1u);
          break;
        }
      }
    }
    barrier();
    const bool stop = s_done == 64u;
    barrier();
    if (stop) break;
    b0 = b1;
  }
  if (inside) image[pixel] = uvec2(packHalf2x16(color.rg), packHalf2x16(vec2(color.b, alpha)));
  atomicAdd(s_frags, frags);
  if (alpha > 0.0) atomicAdd(s_hair, 1u);
  barrier();
  if (lid == 0u) {
    atomicAdd(counters[4], s_frags);
    atomicAdd(counters[5], s_hair);
    if (s_hair > 0u) {  // the rectangle of tiles with hair, for the composite (after the layer's pixels)
      const uint at = pc.size.x * pc.size.y;
      atomicMax(image[at].x, 65535u - gl_WorkGroupID.x);
      atomicMax(image[at].y, 65535u - gl_WorkGroupID.y);
      atomicMax(image[at + 1u].x, gl_WorkGroupID.x + 1u);
      atomicMax(image[at + 1u].y, gl_WorkGroupID.y + 1u);
    }
  }
}
