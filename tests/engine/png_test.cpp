#include <tressvk/engine/png.hpp>

#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

#include <filesystem>

using namespace tressvk::engine;
using Catch::Matchers::ContainsSubstring;

namespace {
Pixels gradient(uint32_t w, uint32_t h) {
  Pixels pixels;
  pixels.width = w;
  pixels.height = h;
  pixels.texel_size = 4;
  for (uint32_t i = 0; i < w * h; ++i) {
    pixels.data.push_back(static_cast<uint8_t>(i * 10));
    pixels.data.push_back(static_cast<uint8_t>(255 - i));
    pixels.data.push_back(static_cast<uint8_t>(i * 3));
    pixels.data.push_back(static_cast<uint8_t>(i % 2 ? 255 : 128));
  }
  return pixels;
}
}  // namespace

TEST_CASE("write_png writes RGBA pixels that read back identically, swizzling BGRA", "[engine]") {
  const Pixels pixels = gradient(5, 3);
  const auto dir = std::filesystem::temp_directory_path() / "tressvk_png_test" / "nested";
  std::filesystem::remove_all(dir.parent_path());
  write_png(dir / "rgba.png", pixels);  // creates the missing directories
  const Pixels rgba = read_png(dir / "rgba.png");
  CHECK(rgba.width == 5);
  CHECK(rgba.height == 3);
  CHECK(rgba.data == pixels.data);

  write_png(dir / "bgra.png", pixels, /*bgra=*/true);
  const Pixels swapped = read_png(dir / "bgra.png");
  REQUIRE(swapped.data.size() == pixels.data.size());
  bool same = true;
  for (size_t i = 0; i < pixels.data.size(); i += 4)
    same = same && swapped.data[i] == pixels.data[i + 2] && swapped.data[i + 1] == pixels.data[i + 1] &&
           swapped.data[i + 2] == pixels.data[i] && swapped.data[i + 3] == pixels.data[i + 3];
  CHECK(same);
  std::filesystem::remove_all(dir.parent_path());
}

TEST_CASE("PNG errors name the file", "[engine]") {
  Pixels floats;
  floats.width = 2;
  floats.height = 2;
  floats.texel_size = 16;
  floats.data.resize(64);
  CHECK_THROWS_WITH(write_png("/tmp/tressvk_png_test_bad.png", floats), ContainsSubstring("tressvk_png_test_bad.png"));
  CHECK_THROWS_WITH(read_png("/nonexistent/tressvk_missing.png"), ContainsSubstring("tressvk_missing.png"));
}

TEST_CASE("compare_rgba8 measures channel differences against a threshold", "[engine]") {
  const Pixels a = gradient(4, 4);
  Pixels b = a;
  CHECK(compare_rgba8(a, b, 0).max_channel_diff == 0);
  CHECK(compare_rgba8(a, b, 0).pixels_over == 0);
  b.data[0] = static_cast<uint8_t>(b.data[0] + 3);   // pixel 0: red +3
  b.data[4 * 5 + 2] = static_cast<uint8_t>(b.data[4 * 5 + 2] + 10);  // pixel 5: blue +10
  const PixelDiff d = compare_rgba8(a, b, 4);
  CHECK(d.max_channel_diff == 10);
  CHECK(d.pixels_over == 1);  // only the +10 exceeds 4
  CHECK(d.fraction_over == 1.0 / 16.0);
  CHECK(d.mean_channel_diff == 13.0 / 64.0);
  const Pixels visual = diff_image(a, b, 4);
  CHECK(visual.data[0] == 12);
  CHECK(visual.data[3] == 255);
  Pixels small = gradient(2, 2);
  CHECK_THROWS_AS(compare_rgba8(a, small, 0), Error);
}
