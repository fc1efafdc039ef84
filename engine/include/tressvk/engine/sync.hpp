// Small synchronization2 helpers. Every barrier in the engine goes through these, so the states are explicit.
#pragma once

#include <volk.h>

namespace tressvk::engine {

// Where an image or buffer was last used (or will be used next): stage, access and, for images, layout.
struct ResourceState {
  VkPipelineStageFlags2 stage = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = VK_ACCESS_2_NONE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
};

namespace state {
inline constexpr ResourceState kUndefined{VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_IMAGE_LAYOUT_UNDEFINED};
inline constexpr ResourceState kColorAttachment{VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                                                VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
                                                    VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT,
                                                VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
inline constexpr ResourceState kDepthAttachment{
    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
    VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL};
// Depth as a classic render pass leaves it (RenderPassTarget).
inline constexpr ResourceState kDepthStencilAttachment{
    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
    VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
inline constexpr ResourceState kTransferSrc{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                                            VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL};
inline constexpr ResourceState kTransferDst{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                            VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL};
inline constexpr ResourceState kFragmentSampled{VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                                                VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                                                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
inline constexpr ResourceState kComputeReadWrite{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                                 VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                                                     VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                                 VK_IMAGE_LAYOUT_GENERAL};
inline constexpr ResourceState kAllCommands{VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                            VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
                                            VK_IMAGE_LAYOUT_UNDEFINED};
inline constexpr ResourceState kHostRead{VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT,
                                         VK_IMAGE_LAYOUT_UNDEFINED};
}  // namespace state

void cmd_image_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, const ResourceState& from,
                       const ResourceState& to);
void cmd_buffer_barrier(VkCommandBuffer cmd, VkBuffer buffer, const ResourceState& from, const ResourceState& to);
// A global memory barrier (cheapest to write; fine for buffers).
void cmd_memory_barrier(VkCommandBuffer cmd, const ResourceState& from, const ResourceState& to);

// One semaphore of a vkQueueSubmit2, waited on or signalled at `stages`.
VkSemaphoreSubmitInfo semaphore_submit_info(VkSemaphore semaphore, VkPipelineStageFlags2 stages);
// Submits one command buffer (vkQueueSubmit2), waiting on and signalling at most one semaphore each (null: none),
// then signalling `fence` (may be VK_NULL_HANDLE). Throws engine::Error naming the failed call.
void queue_submit(VkQueue queue, VkCommandBuffer cmd, VkFence fence, const VkSemaphoreSubmitInfo* wait = nullptr,
                  const VkSemaphoreSubmitInfo* signal = nullptr);

}  // namespace tressvk::engine
