#include <tressvk/engine/png.hpp>

#include <catch2/catch_test_macros.hpp>

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
#include <stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#include <filesystem>

using namespace tressvk::engine;

TEST_CASE("write_png writes RGBA pixels that read back identically, swizzling BGRA", "[engine]") {
  Pixels pixels;
  pixels.width = 5;
  pixels.height = 3;
  pixels.texel_size = 4;
  for (uint32_t i = 0; i < pixels.width * pixels.height; ++i) {
    pixels.data.push_back(static_cast<uint8_t>(i * 10));
    pixels.data.push_back(static_cast<uint8_t>(255 - i));
    pixels.data.push_back(static_cast<uint8_t>(i * 3));
    pixels.data.push_back(static_cast<uint8_t>(i % 2 ? 255 : 128));
  }
  const auto dir = std::filesystem::temp_directory_path() / "tressvk_png_test" / "nested";
  std::filesystem::remove_all(dir.parent_path());
  for (const bool bgra : {false, true}) {
    const auto path = dir / (bgra ? "bgra.png" : "rgba.png");
    write_png(path, pixels, bgra);  // creates the missing directories
    int w = 0, h = 0, n = 0;
    unsigned char* read = stbi_load(path.c_str(), &w, &h, &n, 4);
    REQUIRE(read != nullptr);
    CHECK(w == 5);
    CHECK(h == 3);
    bool same = true;
    for (size_t i = 0; i < pixels.data.size(); ++i) {
      const size_t channel = i % 4;
      const size_t swapped = bgra && channel != 1 && channel != 3 ? (i - channel) + (2 - channel) : i;
      if (read[i] != pixels.data[swapped]) same = false;
    }
    stbi_image_free(read);
    CHECK(same);
  }
  std::filesystem::remove_all(dir.parent_path());
}

TEST_CASE("write_png refuses pixels that are not 8-bit RGBA and names the file", "[engine]") {
  Pixels pixels;
  pixels.width = 2;
  pixels.height = 2;
  pixels.texel_size = 16;
  pixels.data.resize(64);
  try {
    write_png("/tmp/tressvk_png_test_bad.png", pixels);
    FAIL("write_png accepted float pixels");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find("tressvk_png_test_bad.png") != std::string::npos);
  }
}
