// GPU timestamps: a query pool of N slots, written in command buffers, read back as milliseconds.
// On lavapipe timestamps measure CPU time (the "GPU" is the CPU); on real GPUs they measure the GPU.
#pragma once

#include <tressvk/engine/device.hpp>
#include <tressvk/engine/handle.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace tressvk::engine {

// Milliseconds between two raw timestamps, honouring timestampValidBits (counters may wrap at 2^bits).
double timestamp_delta_ms(uint64_t begin, uint64_t end, double period_ns, uint32_t valid_bits);

class TimestampQueries {
 public:
  TimestampQueries() = default;
  // Does nothing useful (every read returns empty) when the device's queue has no timestamps.
  TimestampQueries(const Device& device, uint32_t count);

  bool supported() const { return static_cast<bool>(pool_); }
  uint32_t count() const { return count_; }
  // Resets every slot; record before the first write of a frame, outside a render pass.
  void cmd_reset(VkCommandBuffer cmd) const;
  void cmd_write(VkCommandBuffer cmd, uint32_t slot, VkPipelineStageFlags2 stage) const;
  // Waits for the results of slots [0, count) and returns the raw values; empty when unsupported.
  std::vector<uint64_t> fetch() const;
  // Milliseconds between two slots (waits for the results); empty when unsupported.
  std::optional<double> elapsed_ms(uint32_t begin_slot, uint32_t end_slot) const;

 private:
  VkDevice device_of_pool_ = VK_NULL_HANDLE;
  DeviceHandle<VkQueryPool> pool_;
  uint32_t count_ = 0;
  double period_ns_ = 1.0;
  uint32_t valid_bits_ = 64;
};

}  // namespace tressvk::engine
