// The demo's options for the renderer's still pictures: a square frame, no head motion and a zero time step, so the
// hair stays in its baked rest pose (the images test the renderer and do not change when the simulation model is
// tuned), with a reduced groom of `guides` guides and `follows` follow hairs each.
#pragma once

#include "demo_options.hpp"

#include <cstdint>

namespace tressvk::test {

inline demo::Options still_frame_options(uint32_t size, uint32_t guides, uint32_t follows) {
  demo::Options o;
  o.width = size;
  o.height = size;
  o.animate = demo::Animation::none;
  o.frame_time = 0.0;
  o.guides = guides;
  o.follows = follows;
  return o;
}

}  // namespace tressvk::test
