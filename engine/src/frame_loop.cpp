#include <tressvk/engine/frame_loop.hpp>
#include <tressvk/engine/sync.hpp>

namespace tressvk::engine {

FrameLoop::FrameLoop(const Device& device, uint32_t frames_in_flight, uint32_t timestamp_slots,
                     OnComplete on_complete)
    : device_(device), on_complete_(std::move(on_complete)) {
  if (frames_in_flight == 0) throw Error("FrameLoop: frames_in_flight must be at least 1");
  VkCommandPoolCreateInfo pci{};
  pci.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pci.queueFamilyIndex = device.queue_family();
  vk_check(vkCreateCommandPool(device.device(), &pci, nullptr, &pool_), "vkCreateCommandPool");
  slots_.resize(frames_in_flight);
  try {
    for (Slot& slot : slots_) {
      VkCommandBufferAllocateInfo ai{};
      ai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
      ai.commandPool = pool_;
      ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
      ai.commandBufferCount = 1;
      vk_check(vkAllocateCommandBuffers(device.device(), &ai, &slot.cmd), "vkAllocateCommandBuffers");
      VkFenceCreateInfo fi{};
      fi.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
      vk_check(vkCreateFence(device.device(), &fi, nullptr, &slot.fence), "vkCreateFence");
      slot.timestamps = TimestampQueries(device, timestamp_slots);
    }
  } catch (...) {
    for (Slot& slot : slots_)
      if (slot.fence) vkDestroyFence(device.device(), slot.fence, nullptr);
    vkDestroyCommandPool(device.device(), pool_, nullptr);
    throw;
  }
}

FrameLoop::~FrameLoop() {
  for (Slot& slot : slots_)
    if (slot.pending) vkWaitForFences(device_.device(), 1, &slot.fence, VK_TRUE, UINT64_MAX);
  for (Slot& slot : slots_) vkDestroyFence(device_.device(), slot.fence, nullptr);
  vkDestroyCommandPool(device_.device(), pool_, nullptr);  // frees the command buffers
}

void FrameLoop::complete(Slot& slot, bool report) {
  if (!slot.pending) return;
  vk_check(vkWaitForFences(device_.device(), 1, &slot.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  vk_check(vkResetFences(device_.device(), 1, &slot.fence), "vkResetFences");
  slot.pending = false;
  if (report && on_complete_) on_complete_(slot.frame);
}

const FrameLoop::Frame& FrameLoop::begin() {
  if (recording_) throw Error("FrameLoop::begin: the previous frame was not ended");
  const uint64_t number = next_number_++;
  Slot& slot = slots_[number % slots_.size()];
  complete(slot, true);  // frames complete in order: this slot holds the oldest submitted frame
  vk_check(vkResetCommandBuffer(slot.cmd, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vk_check(vkBeginCommandBuffer(slot.cmd, &bi), "vkBeginCommandBuffer");
  slot.timestamps.cmd_reset(slot.cmd);
  slot.frame = Frame{number, static_cast<uint32_t>(number % slots_.size()), slot.cmd, &slot.timestamps};
  recording_ = &slot;
  return slot.frame;
}

void FrameLoop::end() {
  if (!recording_) throw Error("FrameLoop::end: no frame was begun");
  Slot& slot = *recording_;
  recording_ = nullptr;
  vk_check(vkEndCommandBuffer(slot.cmd), "vkEndCommandBuffer");
  queue_submit(device_.queue(), slot.cmd, slot.fence);
  slot.pending = true;
}

void FrameLoop::finish() {
  if (recording_) throw Error("FrameLoop::finish: a frame is still being recorded");
  // Oldest first: the slot after the most recently used one holds the oldest pending frame.
  const size_t n = slots_.size();
  for (size_t i = 0; i < n; ++i) complete(slots_[(next_number_ + i) % n], true);
}

}  // namespace tressvk::engine
