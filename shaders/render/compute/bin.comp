#version 460
#extension GL_GOOGLE_include_directive : require
// Compute rasterizer, passes 2 and 4: one thread per segment walks the 8 x 8 tiles its footprint touches (the
// pixels whose centre lies within half its width plus half a pixel of it) and, per tile not entirely in front of
// it in the host's depth, counts it (kScatter = 0) or writes (its depth nearest the tile centre, segment) at the
// tile's cursor
// (kScatter = 1). Both passes take exactly the same decisions. The scatter pass also packs the fine pass's list of
// tiles with entries.
layout(local_size_x = 64) in;
layout(constant_id = 0) const uint kScatter = 0u;
#include "render/compute/raster_layout.glsl"

// Slack of the footprint test, pixels: far more than the float rounding of fine.comp's exact test (1e-3 px at 4K), so
// a tile whose pixels the segment covers is never skipped.
const float kBinSlack = 1.0 / 16.0;

void main() {
  if (kScatter != 0u) {
    // Also lists the tiles with entries for the fine pass, each at its weight bucket's cursor (scan.comp placed
    // the buckets, heaviest first; the order within a bucket does not change the image), since the scatter is the
    // first pass after the scan and runs at least a thread per segment.
    const uint tiles_count = pc.size.z * pc.size.w;
    const uint cursors = tile_list_buckets_at(tiles_count) + kBuckets, entries_at = tile_list_entries_at(tiles_count);
    for (uint t = gl_GlobalInvocationID.x; t < tiles_count; t += 64u * gl_NumWorkGroups.x) {
      const uint v = tiles[t];
      if (v > 0u) tiles[entries_at + atomicAdd(tiles[cursors + weight_bucket(v)], 1u)] = t;
    }
  }
  const uint seg = gl_GlobalInvocationID.x;
  if (seg >= pc.params.w) return;
  const uint n = dc.counts.x;
  const uint va = seg / (n - 1u) * n + seg % (n - 1u);
  const vec4 a = verts[2u * va];
  const vec4 b = verts[2u * va + 2u];
  if (a.z < 0.0 || b.z < 0.0 || min(a.z, b.z) > 1.0) return;  // behind the eye or beyond the far plane
  const vec2 d = b.xy - a.xy;
  const float len2 = dot(d, d);
  if (len2 < 1e-8) return;  // no screen extent (pointing at the eye): the neighbours cover it
  const float reach = 0.5 * max(a.w, b.w) + 0.5;
  const vec2 lo = max(min(a.xy, b.xy) - reach, vec2(0.0));
  const vec2 hi = min(max(a.xy, b.xy) + reach, vec2(pc.size.xy));
  if (any(greaterThanEqual(lo, hi))) return;
  const uvec2 t0 = uvec2(lo) / kTile;
  const uvec2 t1 = min(uvec2(ceil(hi)) / kTile, pc.size.zw - 1u);
  const float zmin = min(a.z, b.z);
  const uint tiles_count = pc.size.z * pc.size.w;
  // The footprint: the rectangle along the segment, reach to either side, no caps (fine.comp covers a pixel only
  // where its centre projects onto the segment, t in [0, 1], within half the width plus half a pixel of it). A
  // tile is taken when the rectangle meets the square of its pixel centres (half-size 3.5 px around the tile
  // centre): separating axes x, y, along and across the segment, each side widened by kBinSlack.
  const float len = sqrt(len2);
  const vec2 e = d / len, nrm = vec2(-e.y, e.x);
  const float half_centres = 0.5 * float(kTile - 1u);
  const vec2 ext = abs(nrm) * reach + (half_centres + kBinSlack);  // the rectangle's half-width + the square's, on x, y
  const vec2 mid = 0.5 * (a.xy + b.xy);
  const vec2 half_d = 0.5 * abs(d);
  const float along_a = dot(a.xy, e), across_a = dot(a.xy, nrm);
  const float square_e = half_centres * (abs(e.x) + abs(e.y)) + kBinSlack;  // the square's half-extent on e and nrm
  uint binned = 0u;
  for (uint ty = t0.y; ty <= t1.y; ++ty) {
    for (uint tx = t0.x; tx <= t1.x; ++tx) {
      const uint t = ty * pc.size.z + tx;
      if (zmin > uintBitsToFloat(tiles[3u * tiles_count + t])) continue;  // behind the host depth everywhere
      const vec2 c = (vec2(tx, ty) + 0.5) * float(kTile);
      if (any(greaterThan(abs(c - mid), half_d + ext))) continue;  // separated on x or y
      const float ce = dot(c, e) - along_a, cn = dot(c, nrm) - across_a;
      if (ce < -square_e || ce > len + square_e || abs(cn) > reach + square_e) continue;  // along or across
      const float s = clamp(dot(c - a.xy, d) / len2, 0.0, 1.0);
      if (kScatter == 0u) {
        atomicAdd(tiles[t], 1u);
        ++binned;
      } else {
        // The cursor counts within the tile's block of 1024 tiles; the block's offset is scan.comp's [6T + 2b].
        const uint at = atomicAdd(tiles[2u * tiles_count + t], 1u) + tiles[6u * tiles_count + 2u * (t / 1024u)];
        // Sort key: the segment's depth at its point nearest the tile's centre (not its mid-point: a segment
        // is often longer than a tile, and what matters is its depth where it crosses this tile).
        if (at < pc.params.x) entries[at] = uvec2(floatBitsToUint(max(mix(a.z, b.z, s), 0.0)), seg);
      }
    }
  }
  if (kScatter == 0u && binned > 0u) {
    atomicAdd(counters[0], binned);
    atomicAdd(counters[2], 1u);
  }
}
