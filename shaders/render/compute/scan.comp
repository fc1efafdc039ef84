#version 460
#extension GL_GOOGLE_include_directive : require
// Compute rasterizer, pass 3: exclusive prefix sum of the tiles' segment counts -> first entry and scatter cursor
// per tile. One workgroup of 1024 threads: each sums a contiguous chunk of ceil(T / 1024) tiles, a work-efficient
// (Blelloch) scan in shared memory combines the 1024 chunk sums in 2 log2(1024) steps, and each thread writes its
// chunk's offsets. 1080p has 32,400 tiles (32 per thread), 4K 129,600 (127 per thread).
layout(local_size_x = 1024) in;
#include "render/compute/raster_layout.glsl"

shared uint s_sum[1024];

void main() {
  const uint tiles_count = pc.size.z * pc.size.w;
  const uint i = gl_LocalInvocationIndex;
  const uint chunk = (tiles_count + 1023u) / 1024u;
  const uint first = min(i * chunk, tiles_count);
  const uint last = min(first + chunk, tiles_count);
  uint sum = 0u;
  for (uint t = first; t < last; ++t) sum += tiles[t];
  s_sum[i] = sum;
  barrier();
  // Up-sweep.
  for (uint stride = 1u; stride < 1024u; stride <<= 1u) {
    const uint k = (i + 1u) * stride * 2u - 1u;
    if (k < 1024u) s_sum[k] += s_sum[k - stride];
    barrier();
  }
  if (i == 0u) s_sum[1023] = 0u;
  barrier();
  // Down-sweep.
  for (uint stride = 512u; stride >= 1u; stride >>= 1u) {
    const uint k = (i + 1u) * stride * 2u - 1u;
    if (k < 1024u) {
      const uint left = s_sum[k - stride];
      s_sum[k - stride] = s_sum[k];
      s_sum[k] += left;
    }
    barrier();
  }
  uint offset = s_sum[i];
  for (uint t = first; t < last; ++t) {
    tiles[tiles_count + t] = offset;
    tiles[2u * tiles_count + t] = offset;
    offset += tiles[t];
  }
  if (i == 1023u && offset > pc.params.x) counters[1] = offset - pc.params.x;  // entries that did not fit
}
