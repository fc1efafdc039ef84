// The one translation unit that compiles stb_image_write for the engine.
#include <tressvk/engine/png.hpp>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO_FAILURE_OUTPUT
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wcast-align"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#endif
#include <stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

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

}  // namespace tressvk::engine
