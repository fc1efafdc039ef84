// The engine's embedded shaders (compiled from engine/shaders/ at build time).
#pragma once

#include <cstdint>
#include <span>

namespace tressvk::engine::shaders {

// A triangle from push constants: `vec4 position[3]` (clip space) then `vec4 color[3]` (linear RGBA), 96 bytes.
std::span<const uint32_t> triangle_vert();
std::span<const uint32_t> triangle_frag();  // interpolated vertex colour

struct TrianglePush {
  float position[3][4];
  float color[3][4];
};
static_assert(sizeof(TrianglePush) == 96);

}  // namespace tressvk::engine::shaders
