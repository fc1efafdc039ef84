// The brute-force reference of the compute strand rasterizer, in double: every fragment of every segment (the
// same per-vertex screen positions, widths, depths and colours the GPU computed, the same box-filter coverage
// and the same host depth test), kept and fully depth-sorted per pixel by the fragment's own depth, composited
// front to back with no early termination. What it measures is the rasterizer's approximations (per-tile
// sorting by segment depth, depth slices, early termination, half-float output), not the shading model.
#pragma once

#include <cstdint>
#include <vector>

namespace tressvk::reference {

struct StrandRasterInput {
  uint32_t width = 0, height = 0;
  uint32_t vertices_per_strand = 0, strands = 0;
  const float* vertices = nullptr;    // per vertex: x px, y px, depth (< 0: behind the eye), width px, r, g, b, opacity
  const float* host_depth = nullptr;  // width * height, Vulkan 0..1 (hair at a depth <= it is visible)
};

// Premultiplied linear RGBA per pixel, row-major from the top row.
struct HairLayer {
  uint32_t width = 0, height = 0;
  std::vector<double> rgba;
};

// `fragments` (optional): fragments composited (coverage > 0, in front of the host depth).
HairLayer render_strands_reference(const StrandRasterInput& input, uint64_t* fragments = nullptr);

// The GPU's layer (4 half floats per pixel).
HairLayer layer_from_half(uint32_t width, uint32_t height, const uint16_t* halves);

// Error of `actual` against `reference` in 1/255 units, per channel: the colour channels as displayed over black
// (sRGB-encoded premultiplied colour, x255) and alpha (x255). Statistics over the pixels where either layer has
// alpha >= 0.5/255 ("hair pixels"); mean and 99th percentile over all their channels, and the maximum.
struct LayerError {
  double mean = 0, p99 = 0, max = 0;
  uint64_t hair_pixels = 0;
};
LayerError compare_layers(const HairLayer& actual, const HairLayer& reference);
// Sets e's mean, 99th percentile and maximum from per-channel `errors` (left as they are when there are none).
void summarise_errors(std::vector<double> errors, LayerError& e);

}  // namespace tressvk::reference
