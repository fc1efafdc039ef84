// PNG output (stb_image_write) and input (stb_image), and an 8-bit image comparison for golden-image tests.
#pragma once

#include <tressvk/engine/image.hpp>

#include <filesystem>

namespace tressvk::engine {

// Writes 8-bit RGBA pixels (BGRA images are swizzled) as a PNG; creates the parent directory. Throws Error
// naming the path on failure.
void write_png(const std::filesystem::path& path, const Pixels& pixels, bool bgra = false);

// Reads a PNG as 8-bit RGBA (any channel count is expanded). Throws Error naming the path and stb's reason.
Pixels read_png(const std::filesystem::path& path);

// Per-channel differences between two 8-bit RGBA images of the same size.
struct PixelDiff {
  uint32_t max_channel_diff = 0;     // largest |a - b| over all channels, 0..255
  double mean_channel_diff = 0.0;    // mean |a - b| over all channels
  uint64_t pixels_over = 0;          // pixels with any channel differing by more than the threshold
  double fraction_over = 0.0;        // pixels_over / pixel count
};
// Throws Error when the sizes or formats differ. `threshold` is the per-channel difference that counts a pixel.
PixelDiff compare_rgba8(const Pixels& a, const Pixels& b, uint32_t threshold);
// An image of |a - b| per channel (alpha forced opaque, differences scaled by `gain`) for looking at failures.
Pixels diff_image(const Pixels& a, const Pixels& b, uint32_t gain = 4);

}  // namespace tressvk::engine
