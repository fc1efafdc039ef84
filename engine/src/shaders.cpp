#include <tressvk/engine/shaders.hpp>

#include "tressvk_engine_spirv.h"

namespace tressvk::engine::shaders {

std::span<const uint32_t> triangle_vert() { return k_spv_triangle_vert; }
std::span<const uint32_t> triangle_frag() { return k_spv_triangle_frag; }

}  // namespace tressvk::engine::shaders
