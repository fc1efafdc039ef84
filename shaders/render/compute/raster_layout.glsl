// The compute strand rasterizer's resources (plugin/src/render/compute/). Set 0 bindings 0-4 are the hair
// passes' (hair_layout.glsl: constants, positions, tangents, guide info, anchors); 5-12 are the rasterizer's.
// Must match plugin/src/render/compute/state.hpp.
#include "render/hair_layout.glsl"

layout(set = 0, binding = 5) uniform sampler2D shadow_map;   // host shadow map (bound to the depth view if none)
layout(set = 0, binding = 6) uniform sampler2D host_depth;   // host opaque depth, Vulkan 0..1, LESS_OR_EQUAL
// Per drawn vertex v: [2v] = (x px, y px, depth 0..1 or -1 if culled, width px) (project.comp), [2v+1] = (linear rgb,
// opacity) (vertex.comp, which runs beside the scan: no pass reads this buffer while it writes); shaded per fragment,
// after the D drawn vertices [2(D + v)] = (point, along) and [2(D + v) + 1] = (tangent, tint) (project.comp).
layout(std430, set = 0, binding = 7) buffer Verts { vec4 verts[]; };
// Per tile t of T: [t] segment count, [T+t] first entry, [2T+t] scatter cursor, [3T+t] farthest host depth bits,
// [4T+t] first split slot (kNotSplit: composited whole), [5T+t] its work items finished (fine.comp); first entry and
// cursor count within the tile's block of 1024 tiles, whose offset (entries, split slots) is [6T + 2b] (scan.comp).
// After the blocks' words, at L = tile_list_at(T): the fine pass's indirect dispatch (x, y, z), the number of
// tiles with entries and the number with more than kSplitFewAt entries (scan.comp); from tile_list_buckets_at(T) the tiles with entries per weight bucket (kBuckets counts, then
// kBuckets cursors); from tile_list_entries_at(T) those tiles, heaviest bucket first (the fine pass runs a
// workgroup per listed tile, not per tile, and the tiles that take longest start first).
layout(std430, set = 0, binding = 8) buffer Tiles { uint tiles[]; };
uint tile_list_at(uint tiles_count) { return 6u * tiles_count + 2u * ((tiles_count + 1023u) / 1024u); }
uint tile_list_buckets_at(uint tiles_count) { return tile_list_at(tiles_count) + 8u; }
// A tile's weight bucket: eighths of an octave of its entry count, the largest counts in bucket 0 (counts from
// 2^16 on share it). A fine workgroup's time grows with its tile's entries, and the pass ends when its longest
// workgroup does: started last, a heavy tile ran on alone for the last third of the pass (measured on an NVIDIA
// H100); started first, it runs while the light tiles fill the GPU around it.
const uint kBuckets = 128u;
uint weight_bucket(uint count) {
  return kBuckets - 1u - min((floatBitsToUint(float(count)) >> 20u) - (127u << 3u), kBuckets - 1u);
}
uint tile_list_entries_at(uint tiles_count) { return tile_list_buckets_at(tiles_count) + 2u * kBuckets; }
const uint kListRow = 32768u;  // listed tiles per row of the fine pass's dispatch (within maxComputeWorkGroupCount)
// Tile entries: x = sort key (depth bits), y = segment index.
layout(std430, set = 0, binding = 9) buffer Entries { uvec2 entries[]; };
// 0: entries requested, 1: entries dropped (over capacity), 2: segments binned, 3: entries dropped from an
// over-full depth bin, 4: fragments composited, 5: hair pixels, 6: tiles that needed depth slices, 7: tiles split
// across workgroups.
layout(std430, set = 0, binding = 10) buffer Counters { uint counters[]; };
// Output, per pixel: premultiplied rgba as two packHalf2x16 words.
layout(std430, set = 0, binding = 11) buffer Image { uvec2 image[]; };
// Capture only: the host depth the fine pass read, per pixel.
layout(std430, set = 0, binding = 12) buffer Capture { float capture_depth[]; };

// Over-full tiles' work items (scan.comp -> fine.comp): [0], [1] the indirect dispatch (slots used, 1, 1) of the
// split pass recorded after the fine pass, [2], [3] that of the one recorded before it (one of the two is empty),
// [4 + slot] = (tile, item index).
layout(std430, set = 0, binding = 14) buffer Split { uvec2 split_items[]; };
// Per split slot, 64 pixels: the item's premultiplied rgba (two packHalf2x16 words), merged front to back by the
// tile's last item to finish (written and read by different workgroups of one dispatch: coherent).
layout(std430, set = 0, binding = 15) coherent buffer Partials { uvec2 partials[]; };

// Deep opacity map of the hair seen from the shadowed light, kDomSize^2 texels: [texel] nearest hair depth (m, float
// bits), then per texel its kDomLayers layers of fibre density side by side (fixed point, kDomUnit per texel fully
// covered by one fibre): [T + 4 texel + layer], T = kDomSize^2, which dom_layers reads as one uvec4 per texel. The
// vertex shading reads 3 x 3 texels per vertex: its layers in one load per texel instead of one per layer, and the
// map's layer pass adds a texel's layers within one cache line (measured on an NVIDIA H100, 100,000 x 32 strands at
// 1080p, against the layers in planes of their own: the shading step 0.578 -> 0.361 ms, the count step beside the
// layer pass 0.634 -> 0.608; the same image to the bit).
layout(std430, set = 0, binding = 13) buffer Dom { uint dom[]; };
layout(std430, set = 0, binding = 13) readonly buffer DomLayers { uvec4 dom_layers[]; };  // the same buffer

layout(push_constant) uniform Raster {
  uvec4 size;    // x: width, y: height, z: tiles x, w: tiles y
  uvec4 params;  // x: entry capacity, y: strands drawn, z: flags (1 capture, 2 reverse strands), w: segments
  uvec4 split;   // x: split work item slots (partial layers)
} pc;

const uint kTile = 8u;          // tile edge in pixels (8 x 8 = one workgroup of the fine pass)
// A tile with more than kSplitAt entries is composited by ceil(count / kSplit) workgroups, each a contiguous share
// of its depth-key histogram (kSplit* in plugin/src/render/compute/state.hpp; pc.split.x items at most); so is one
// with more than kSplitFewAt entries when at most kSplitFew tiles of the call have that many (scan.comp).
const uint kSplitAt = 8192u;
const uint kSplitFewAt = 2048u;
const uint kSplitFew = 512u;
const uint kSplit = 1024u;
const uint kNotSplit = 0xffffffffu;
const uint kFlagCapture = 1u;
const uint kFlagReverse = 2u;
const uint kFlagShadowed = 4u;   // a shadow map was given: build and read the deep opacity map
const uint kFlagPerFragment = 8u; // shade per fragment in fine.comp (TVK_RASTER_SHADE_PER_FRAGMENT)
const uint kFlagSplitDense = 16u; // scan.comp: split as for a dense groom however few tiles are heavy (tests)
const uint kDomSize = 512u;
const uint kDomLayers = 4u;
const float kDomUnit = 1024.0;
// Layer k holds the fibres between kDomEdge[k] and kDomEdge[k+1] fibre spacings behind the nearest hair.
const float kDomEdge[5] = float[5](0.0, 2.0, 6.0, 14.0, 1e30);

// Light-space depth in metres from the light's clip z (orthographic or perspective light).
float light_metres(float z) {
  const float n = dc.shadow_params.x, f = dc.shadow_params.y;
  return dc.shadow_params.z > 0.5 ? n * f / max(f - z * (f - n), 1e-12) : n + z * (f - n);
}

// The same box-filter coverage as the raster path (hair_shade.glsl): overlap of the strand's cross-section of
// width w (px) centred at distance d from the pixel centre with the pixel's [-1/2, 1/2].
float coverage(float d, float w) { return clamp(min(d + 0.5 * w, 0.5) - max(d - 0.5 * w, -0.5), 0.0, 1.0); }
