// PNG output with stb_image_write.
#pragma once

#include <tressvk/engine/image.hpp>

#include <filesystem>

namespace tressvk::engine {

// Writes 8-bit RGBA pixels (BGRA images are swizzled) as a PNG; creates the parent directory. Throws Error
// naming the path on failure.
void write_png(const std::filesystem::path& path, const Pixels& pixels, bool bgra = false);

}  // namespace tressvk::engine
