// Demo v0 frame: a clear and one triangle into an offscreen colour + depth target, timed with GPU timestamps
// and copied into the frame slot's readback buffer for PNG output. Frames run in flight (engine::FrameLoop):
// the GPU renders frame n+1 while the CPU writes the PNG of frame n. The rendering issue replaces the triangle
// with the scene and the hair passes; the frame structure (timestamps around passes, offscreen target,
// per-slot readback) stays.
#pragma once

#include <tressvk/engine/buffer.hpp>
#include <tressvk/engine/device.hpp>
#include <tressvk/engine/frame_loop.hpp>
#include <tressvk/engine/image.hpp>
#include <tressvk/engine/pipeline.hpp>

#include <optional>
#include <vector>

namespace tressvk::demo {

struct FrameResult {
  engine::Pixels pixels;
  std::optional<double> gpu_ms;  // empty when the queue has no timestamps
};

class DemoRenderer {
 public:
  static constexpr uint32_t kTimestampCount = 2;  // frame begin, frame end

  DemoRenderer(engine::Device& device, uint32_t width, uint32_t height, uint32_t frames_in_flight);
  // Records frame `frame.number` into frame.cmd.
  void record(const engine::FrameLoop::Frame& frame);
  // The finished frame's pixels and GPU time (call from FrameLoop's on_complete).
  FrameResult result(const engine::FrameLoop::Frame& frame) const;

 private:
  engine::Device& device_;
  engine::OffscreenTarget target_;  // shared by the frames in flight: each frame orders itself after the last
  engine::Pipeline triangle_;
  std::vector<engine::Buffer> readback_;  // one per frame slot
};

}  // namespace tressvk::demo
