// The one translation unit that compiles stb_image_write and stb_image (PNG only) for the engine.
#include <tressvk/engine/png.hpp>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO_FAILURE_OUTPUT
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wcast-align"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-function"
#endif
#include <stb_image_write.h>
#include <stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#include <algorithm>
#include <cstdlib>
#include <system_error>
#include <utility>

namespace tressvk::engine {

void write_png(const std::filesystem::path& path, const Pixels& pixels, bool bgra) {
  if (pixels.texel_size != 4 || pixels.data.size() != size_t{4} * pixels.width * pixels.height)
    throw Error("write_png " + path.string() + ": pixels are not 8-bit RGBA");
  if (path.has_parent_path()) {
    std::error_code ec;
    std::filesystem::create_directories(path.parent_path(), ec);
    if (ec) throw Error("write_png: cannot create directory " + path.parent_path().string() + ": " + ec.message());
  }
  const std::vector<uint8_t>* data = &pixels.data;
  std::vector<uint8_t> swizzled;
  if (bgra) {
    swizzled = pixels.data;
    for (size_t i = 0; i < swizzled.size(); i += 4) std::swap(swizzled[i], swizzled[i + 2]);
    data = &swizzled;
  }
  const int w = static_cast<int>(pixels.width);
  const int h = static_cast<int>(pixels.height);
  if (!stbi_write_png(path.c_str(), w, h, 4, data->data(), w * 4))
    throw Error("write_png: cannot write " + path.string());
}

Pixels read_png(const std::filesystem::path& path) {
  int w = 0;
  int h = 0;
  int channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &channels, 4);
  if (!data) throw Error("read_png: cannot read " + path.string() + ": " + stbi_failure_reason());
  Pixels pixels;
  pixels.width = static_cast<uint32_t>(w);
  pixels.height = static_cast<uint32_t>(h);
  pixels.texel_size = 4;
  pixels.data.assign(data, data + static_cast<size_t>(w) * static_cast<size_t>(h) * 4);
  stbi_image_free(data);
  return pixels;
}

namespace {
void check_comparable(const Pixels& a, const Pixels& b) {
  if (a.texel_size != 4 || b.texel_size != 4) throw Error("compare_rgba8: both images must be 8-bit RGBA");
  if (a.width != b.width || a.height != b.height)
    throw Error("compare_rgba8: sizes differ (" + std::to_string(a.width) + "x" + std::to_string(a.height) +
                " vs " + std::to_string(b.width) + "x" + std::to_string(b.height) + ")");
}
}  // namespace

PixelDiff compare_rgba8(const Pixels& a, const Pixels& b, uint32_t threshold) {
  check_comparable(a, b);
  PixelDiff diff;
  uint64_t sum = 0;
  const size_t pixel_count = size_t{a.width} * a.height;
  for (size_t p = 0; p < pixel_count; ++p) {
    uint32_t pixel_max = 0;
    for (size_t c = 0; c < 4; ++c) {
      const uint32_t d = static_cast<uint32_t>(std::abs(int{a.data[p * 4 + c]} - int{b.data[p * 4 + c]}));
      sum += d;
      pixel_max = std::max(pixel_max, d);
    }
    diff.max_channel_diff = std::max(diff.max_channel_diff, pixel_max);
    if (pixel_max > threshold) ++diff.pixels_over;
  }
  if (pixel_count > 0) {
    diff.mean_channel_diff = static_cast<double>(sum) / static_cast<double>(pixel_count * 4);
    diff.fraction_over = static_cast<double>(diff.pixels_over) / static_cast<double>(pixel_count);
  }
  return diff;
}

Pixels diff_image(const Pixels& a, const Pixels& b, uint32_t gain) {
  check_comparable(a, b);
  Pixels out = a;
  for (size_t i = 0; i < out.data.size(); ++i) {
    if (i % 4 == 3) {
      out.data[i] = 255;
      continue;
    }
    const uint32_t d = static_cast<uint32_t>(std::abs(int{a.data[i]} - int{b.data[i]})) * gain;
    out.data[i] = static_cast<uint8_t>(std::min(d, 255u));
  }
  return out;
}

}  // namespace tressvk::engine
