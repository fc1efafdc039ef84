#include <tressvk/engine/check.hpp>
#include <tressvk/engine/sync.hpp>

namespace tressvk::engine {
namespace {

// The stage and access masks every synchronization2 barrier type carries, from one state to the next.
template <typename Barrier>
Barrier barrier_between(VkStructureType type, const ResourceState& from, const ResourceState& to) {
  Barrier b{};
  b.sType = type;
  b.srcStageMask = from.stage;
  b.srcAccessMask = from.access;
  b.dstStageMask = to.stage;
  b.dstAccessMask = to.access;
  return b;
}

// Records one vkCmdPipelineBarrier2 with at most one barrier of each kind.
void record_dependency(VkCommandBuffer cmd, const VkMemoryBarrier2* memory, const VkBufferMemoryBarrier2* buffer,
                       const VkImageMemoryBarrier2* image) {
  VkDependencyInfo dep{};
  dep.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
  dep.memoryBarrierCount = memory ? 1 : 0;
  dep.pMemoryBarriers = memory;
  dep.bufferMemoryBarrierCount = buffer ? 1 : 0;
  dep.pBufferMemoryBarriers = buffer;
  dep.imageMemoryBarrierCount = image ? 1 : 0;
  dep.pImageMemoryBarriers = image;
  vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace

void cmd_image_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, const ResourceState& from,
                       const ResourceState& to) {
  auto b = barrier_between<VkImageMemoryBarrier2>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2, from, to);
  b.oldLayout = from.layout;
  b.newLayout = to.layout;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {aspect, 0, VK_REMAINING_MIP_LEVELS, 0, VK_REMAINING_ARRAY_LAYERS};
  record_dependency(cmd, nullptr, nullptr, &b);
}

void cmd_buffer_barrier(VkCommandBuffer cmd, VkBuffer buffer, const ResourceState& from, const ResourceState& to) {
  auto b = barrier_between<VkBufferMemoryBarrier2>(VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2, from, to);
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.buffer = buffer;
  b.offset = 0;
  b.size = VK_WHOLE_SIZE;
  record_dependency(cmd, nullptr, &b, nullptr);
}

void cmd_memory_barrier(VkCommandBuffer cmd, const ResourceState& from, const ResourceState& to) {
  const auto b = barrier_between<VkMemoryBarrier2>(VK_STRUCTURE_TYPE_MEMORY_BARRIER_2, from, to);
  record_dependency(cmd, &b, nullptr, nullptr);
}

VkSemaphoreSubmitInfo semaphore_submit_info(VkSemaphore semaphore, VkPipelineStageFlags2 stages) {
  VkSemaphoreSubmitInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO;
  info.semaphore = semaphore;
  info.stageMask = stages;
  return info;
}

void queue_submit(VkQueue queue, VkCommandBuffer cmd, VkFence fence, const VkSemaphoreSubmitInfo* wait,
                  const VkSemaphoreSubmitInfo* signal) {
  VkCommandBufferSubmitInfo command{};
  command.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO;
  command.commandBuffer = cmd;
  VkSubmitInfo2 submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2;
  submit.waitSemaphoreInfoCount = wait ? 1 : 0;
  submit.pWaitSemaphoreInfos = wait;
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &command;
  submit.signalSemaphoreInfoCount = signal ? 1 : 0;
  submit.pSignalSemaphoreInfos = signal;
  vk_check(vkQueueSubmit2(queue, 1, &submit, fence), "vkQueueSubmit2");
}

}  // namespace tressvk::engine
