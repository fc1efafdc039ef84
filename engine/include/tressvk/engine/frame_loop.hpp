// Frames in flight, the way a render loop runs: per slot a command buffer, a fence and a timestamp pool.
// begin() waits for the frame that last used the slot (so its results can be read), end() submits without
// waiting. Completed frames are reported in submission order through the on_complete callback, which is where
// the caller reads that frame's timestamps and readback buffers.
#pragma once

#include <tressvk/engine/device.hpp>
#include <tressvk/engine/timestamps.hpp>

#include <cstdint>
#include <functional>
#include <vector>

namespace tressvk::engine {

class FrameLoop {
 public:
  struct Frame {
    uint64_t number = 0;  // 0, 1, 2, ...
    uint32_t slot = 0;    // number % frames_in_flight: index per-frame resources with it
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    const TimestampQueries* timestamps = nullptr;  // this slot's pool, already reset in cmd
  };
  // Called once per submitted frame after the GPU finished it, oldest first.
  using OnComplete = std::function<void(const Frame& frame)>;

  FrameLoop(const Device& device, uint32_t frames_in_flight, uint32_t timestamp_slots, OnComplete on_complete);
  ~FrameLoop();  // waits for every submitted frame (without calling on_complete)
  FrameLoop(const FrameLoop&) = delete;
  FrameLoop& operator=(const FrameLoop&) = delete;

  uint32_t frames_in_flight() const { return static_cast<uint32_t>(slots_.size()); }
  // Waits for the slot's previous frame (reporting it), then begins recording the next frame.
  const Frame& begin();
  // Ends and submits the frame begun last.
  void end();
  // Waits for every submitted frame and reports them.
  void finish();

 private:
  struct Slot {
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    TimestampQueries timestamps;
    Frame frame;
    bool pending = false;  // submitted and not yet reported
  };
  void complete(Slot& slot, bool report);

  const Device& device_;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  std::vector<Slot> slots_;
  OnComplete on_complete_;
  uint64_t next_number_ = 0;
  Slot* recording_ = nullptr;
};

}  // namespace tressvk::engine
