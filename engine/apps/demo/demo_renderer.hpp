// Demo v0 frame: a clear and one triangle into an offscreen colour + depth target, timed with GPU timestamps
// and read back for PNG output. The rendering issue replaces the triangle with the scene and the hair passes;
// the frame structure (timestamps around passes, offscreen target, readback) stays.
#pragma once

#include <tressvk/engine/device.hpp>
#include <tressvk/engine/image.hpp>
#include <tressvk/engine/pipeline.hpp>
#include <tressvk/engine/timestamps.hpp>

#include <optional>

namespace tressvk::demo {

struct FrameResult {
  engine::Pixels pixels;
  std::optional<double> gpu_ms;  // empty when the queue has no timestamps
};

class DemoRenderer {
 public:
  DemoRenderer(engine::Device& device, uint32_t width, uint32_t height);
  FrameResult render(uint32_t frame_index);

 private:
  engine::Device& device_;
  engine::OffscreenTarget target_;
  engine::Pipeline triangle_;
  engine::TimestampQueries timestamps_;
};

}  // namespace tressvk::demo
