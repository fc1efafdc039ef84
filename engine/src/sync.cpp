#include <tressvk/engine/sync.hpp>

namespace tressvk::engine {

void cmd_image_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, const ResourceState& from,
                       const ResourceState& to) {
  VkImageMemoryBarrier2 b{};
  b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2;
  b.srcStageMask = from.stage;
  b.srcAccessMask = from.access;
  b.dstStageMask = to.stage;
  b.dstAccessMask = to.access;
  b.oldLayout = from.layout;
  b.newLayout = to.layout;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {aspect, 0, VK_REMAINING_MIP_LEVELS, 0, VK_REMAINING_ARRAY_LAYERS};
  VkDependencyInfo dep{};
  dep.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

void cmd_buffer_barrier(VkCommandBuffer cmd, VkBuffer buffer, const ResourceState& from, const ResourceState& to) {
  VkBufferMemoryBarrier2 b{};
  b.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2;
  b.srcStageMask = from.stage;
  b.srcAccessMask = from.access;
  b.dstStageMask = to.stage;
  b.dstAccessMask = to.access;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.buffer = buffer;
  b.offset = 0;
  b.size = VK_WHOLE_SIZE;
  VkDependencyInfo dep{};
  dep.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
  dep.bufferMemoryBarrierCount = 1;
  dep.pBufferMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

void cmd_memory_barrier(VkCommandBuffer cmd, const ResourceState& from, const ResourceState& to) {
  VkMemoryBarrier2 b{};
  b.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2;
  b.srcStageMask = from.stage;
  b.srcAccessMask = from.access;
  b.dstStageMask = to.stage;
  b.dstAccessMask = to.access;
  VkDependencyInfo dep{};
  dep.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
  dep.memoryBarrierCount = 1;
  dep.pMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace tressvk::engine
