#include "presenter.hpp"

#include <tressvk/engine/check.hpp>
#include <tressvk/engine/sync.hpp>

#include <algorithm>
#include <cstring>
#include <span>

namespace tressvk::viewer {

namespace {

// The swapchain image as the acquire semaphore hands it over: its wait is at the copy stage, so the layout
// transition is ordered after it.
constexpr VkPipelineStageFlags2 kWriteStages = VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_COPY_BIT;
constexpr engine::ResourceState kAcquired{kWriteStages, VK_ACCESS_2_NONE, VK_IMAGE_LAYOUT_UNDEFINED};
// Cleared (the margin a smaller frame leaves) and copied to.
constexpr engine::ResourceState kWritten{kWriteStages, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL};

VkSemaphore make_semaphore(VkDevice device) {
  VkSemaphoreCreateInfo ci{};
  ci.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO;
  VkSemaphore s = VK_NULL_HANDLE;
  engine::vk_check(vkCreateSemaphore(device, &ci, nullptr, &s), "vkCreateSemaphore");
  return s;
}

}  // namespace

Presenter::Presenter(engine::Device& device, uint32_t width, uint32_t height)
    : device_(device), width_(width), height_(height) {
  if (device.surface() == VK_NULL_HANDLE) throw engine::Error("the viewer's device was made without a window surface");
  const VkDevice dev = device.device();
  VkCommandPoolCreateInfo pci{};
  pci.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pci.queueFamilyIndex = device.queue_family();
  engine::vk_check(vkCreateCommandPool(dev, &pci, nullptr, &pool_), "vkCreateCommandPool");
  VkCommandBufferAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  ai.commandPool = pool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  engine::vk_check(vkAllocateCommandBuffers(dev, &ai, &cmd_), "vkAllocateCommandBuffers");
  VkFenceCreateInfo fci{};
  fci.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  engine::vk_check(vkCreateFence(dev, &fci, nullptr, &done_), "vkCreateFence");
  acquired_ = make_semaphore(dev);
  create_swapchain();
}

Presenter::~Presenter() {
  const VkDevice dev = device_.device();
  vkDeviceWaitIdle(dev);
  destroy_swapchain();
  vkDestroyRenderPass(dev, render_pass_, nullptr);
  vkDestroySemaphore(dev, acquired_, nullptr);
  vkDestroyFence(dev, done_, nullptr);
  vkDestroyCommandPool(dev, pool_, nullptr);
}

void Presenter::create_swapchain() {
  const VkPhysicalDevice gpu = device_.physical_device();
  const VkSurfaceKHR surface = device_.surface();
  VkSurfaceCapabilitiesKHR caps{};
  engine::vk_check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(gpu, surface, &caps),
                   "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
  if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
    throw engine::Error("the window's swapchain images cannot be copied to (no TRANSFER_DST usage)");
  uint32_t n = 0;
  engine::vk_check(vkGetPhysicalDeviceSurfaceFormatsKHR(gpu, surface, &n, nullptr), "vkGetPhysicalDeviceSurfaceFormatsKHR");
  std::vector<VkSurfaceFormatKHR> formats(n);
  engine::vk_check(vkGetPhysicalDeviceSurfaceFormatsKHR(gpu, surface, &n, formats.data()),
                   "vkGetPhysicalDeviceSurfaceFormatsKHR");
  // The frame's bytes are sRGB-encoded 8-bit RGBA; any 8-bit RGBA/BGRA format shows them as they are.
  VkSurfaceFormatKHR chosen{};
  for (const VkSurfaceFormatKHR& f : formats) {
    const bool ok = f.format == VK_FORMAT_B8G8R8A8_SRGB || f.format == VK_FORMAT_B8G8R8A8_UNORM ||
                    f.format == VK_FORMAT_R8G8B8A8_SRGB || f.format == VK_FORMAT_R8G8B8A8_UNORM;
    if (ok && chosen.format == VK_FORMAT_UNDEFINED) chosen = f;
  }
  if (chosen.format == VK_FORMAT_UNDEFINED) throw engine::Error("the window offers no 8-bit RGBA or BGRA swapchain format");
  format_ = chosen.format;
  bgra_ = format_ == VK_FORMAT_B8G8R8A8_SRGB || format_ == VK_FORMAT_B8G8R8A8_UNORM;
  extent_ = caps.currentExtent;
  if (extent_.width == UINT32_MAX) extent_ = {width_, height_};
  extent_.width = std::clamp(extent_.width, caps.minImageExtent.width, caps.maxImageExtent.width);
  extent_.height = std::clamp(extent_.height, caps.minImageExtent.height, caps.maxImageExtent.height);

  VkSwapchainCreateInfoKHR ci{};
  ci.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR;
  ci.surface = surface;
  ci.minImageCount = std::max(caps.minImageCount, 2u);
  if (caps.maxImageCount != 0) ci.minImageCount = std::min(ci.minImageCount, caps.maxImageCount);
  ci.imageFormat = chosen.format;
  ci.imageColorSpace = chosen.colorSpace;
  ci.imageExtent = extent_;
  ci.imageArrayLayers = 1;
  ci.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.preTransform = caps.currentTransform;
  ci.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                          ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                          : static_cast<VkCompositeAlphaFlagBitsKHR>(caps.supportedCompositeAlpha &
                                                                     -caps.supportedCompositeAlpha);
  ci.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // always supported
  ci.clipped = VK_TRUE;
  engine::vk_check(vkCreateSwapchainKHR(device_.device(), &ci, nullptr, &swapchain_), "vkCreateSwapchainKHR");
  engine::vk_check(vkGetSwapchainImagesKHR(device_.device(), swapchain_, &n, nullptr), "vkGetSwapchainImagesKHR");
  images_.resize(n);
  engine::vk_check(vkGetSwapchainImagesKHR(device_.device(), swapchain_, &n, images_.data()), "vkGetSwapchainImagesKHR");
  for (uint32_t i = 0; i < n; ++i) ready_to_present_.push_back(make_semaphore(device_.device()));

  if (render_pass_ == VK_NULL_HANDLE) {
    // The copied frame is loaded and the overlay drawn over it; the pass leaves the image ready to present.
    VkAttachmentDescription color{};
    color.format = format_;
    color.samples = VK_SAMPLE_COUNT_1_BIT;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    color.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &ref;
    VkSubpassDependency deps[2]{};
    deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;  // after the clear and copy
    deps[0].dstSubpass = 0;
    deps[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    deps[0].srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    deps[1].srcSubpass = 0;  // before presentation (the semaphore signalled at ALL_COMMANDS follows it)
    deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    deps[1].dstStageMask = VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT;
    deps[1].dstAccessMask = 0;
    VkRenderPassCreateInfo rci{};
    rci.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
    rci.attachmentCount = 1;
    rci.pAttachments = &color;
    rci.subpassCount = 1;
    rci.pSubpasses = &subpass;
    rci.dependencyCount = 2;
    rci.pDependencies = deps;
    engine::vk_check(vkCreateRenderPass(device_.device(), &rci, nullptr, &render_pass_), "vkCreateRenderPass");
  }
  for (VkImage image : images_) {
    VkImageViewCreateInfo vci{};
    vci.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    vci.image = image;
    vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vci.format = format_;
    vci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    engine::vk_check(vkCreateImageView(device_.device(), &vci, nullptr, &view), "vkCreateImageView");
    views_.push_back(view);
    VkFramebufferCreateInfo fci{};
    fci.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
    fci.renderPass = render_pass_;
    fci.attachmentCount = 1;
    fci.pAttachments = &view;
    fci.width = extent_.width;
    fci.height = extent_.height;
    fci.layers = 1;
    VkFramebuffer fb = VK_NULL_HANDLE;
    engine::vk_check(vkCreateFramebuffer(device_.device(), &fci, nullptr, &fb), "vkCreateFramebuffer");
    framebuffers_.push_back(fb);
  }
}

void Presenter::destroy_swapchain() {
  for (VkFramebuffer fb : framebuffers_) vkDestroyFramebuffer(device_.device(), fb, nullptr);
  for (VkImageView v : views_) vkDestroyImageView(device_.device(), v, nullptr);
  framebuffers_.clear();
  views_.clear();
  for (VkSemaphore s : ready_to_present_) vkDestroySemaphore(device_.device(), s, nullptr);
  ready_to_present_.clear();
  images_.clear();
  if (swapchain_) vkDestroySwapchainKHR(device_.device(), swapchain_, nullptr);
  swapchain_ = VK_NULL_HANDLE;
}

void Presenter::present(const engine::Pixels& pixels, const std::function<void(VkCommandBuffer)>& overlay) {
  const VkDevice dev = device_.device();
  if (pixels.texel_size != 4) throw engine::Error("the viewer presents 8-bit RGBA frames only");
  if (submitted_) {  // the previous copy: its command buffer, staging buffer and acquire semaphore are free after it
    engine::vk_check(vkWaitForFences(dev, 1, &done_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    engine::vk_check(vkResetFences(dev, 1, &done_), "vkResetFences");
    submitted_ = false;
  }
  uint32_t index = 0;
  VkResult r = vkAcquireNextImageKHR(dev, swapchain_, UINT64_MAX, acquired_, VK_NULL_HANDLE, &index);
  if (r == VK_ERROR_OUT_OF_DATE_KHR) {  // the window changed: a new swapchain, and this frame is skipped
    vkDeviceWaitIdle(dev);
    destroy_swapchain();
    create_swapchain();
    return;
  }
  if (r != VK_SUBOPTIMAL_KHR) engine::vk_check(r, "vkAcquireNextImageKHR");

  // Stage the overlap of the frame and the swapchain image.
  const uint32_t w = std::min(pixels.width, extent_.width), h = std::min(pixels.height, extent_.height);
  const VkDeviceSize size = VkDeviceSize{4} * w * h;
  if (staging_.handle() == VK_NULL_HANDLE || staging_.size() < size)
    staging_ = engine::create_buffer(device_, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, engine::MemoryUsage::upload);
  std::vector<uint8_t> staged(size);
  uint8_t* dst = staged.data();
  for (uint32_t y = 0; y < h; ++y) {
    const uint8_t* src = pixels.data.data() + (size_t{y} * pixels.width) * 4;
    uint8_t* row = dst + size_t{y} * w * 4;
    if (!bgra_) {
      std::memcpy(row, src, size_t{w} * 4);
    } else {
      for (uint32_t x = 0; x < w; ++x) {
        row[4 * x + 0] = src[4 * x + 2];
        row[4 * x + 1] = src[4 * x + 1];
        row[4 * x + 2] = src[4 * x + 0];
        row[4 * x + 3] = src[4 * x + 3];
      }
    }
  }
  engine::write_buffer(device_, staging_, std::as_bytes(std::span<const uint8_t>(staged)));

  engine::vk_check(vkResetCommandBuffer(cmd_, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  engine::vk_check(vkBeginCommandBuffer(cmd_, &bi), "vkBeginCommandBuffer");
  const VkImage image = images_[index];
  engine::cmd_image_barrier(cmd_, image, VK_IMAGE_ASPECT_COLOR_BIT, kAcquired, kWritten);
  VkClearColorValue background{};
  background.float32[0] = 0.05f;
  background.float32[1] = 0.055f;
  background.float32[2] = 0.065f;
  background.float32[3] = 1.0f;
  VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdClearColorImage(cmd_, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &background, 1, &range);
  engine::cmd_image_barrier(cmd_, image, VK_IMAGE_ASPECT_COLOR_BIT, kWritten, kWritten);
  VkBufferImageCopy copy{};
  copy.bufferRowLength = w;
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {w, h, 1};
  vkCmdCopyBufferToImage(cmd_, staging_.handle(), image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
  // The render pass takes the image from TRANSFER_DST to PRESENT_SRC (its external dependency orders it after
  // the copy), with the overlay drawn over the frame.
  VkRenderPassBeginInfo rbi{};
  rbi.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
  rbi.renderPass = render_pass_;
  rbi.framebuffer = framebuffers_[index];
  rbi.renderArea.extent = extent_;
  vkCmdBeginRenderPass(cmd_, &rbi, VK_SUBPASS_CONTENTS_INLINE);
  if (overlay) overlay(cmd_);
  vkCmdEndRenderPass(cmd_);
  engine::vk_check(vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");

  const VkSemaphoreSubmitInfo wait = engine::semaphore_submit_info(acquired_, kWriteStages);
  const VkSemaphoreSubmitInfo signal =
      engine::semaphore_submit_info(ready_to_present_[index], VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
  engine::queue_submit(device_.queue(), cmd_, done_, &wait, &signal);
  submitted_ = true;

  VkPresentInfoKHR pi{};
  pi.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR;
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = &ready_to_present_[index];
  pi.swapchainCount = 1;
  pi.pSwapchains = &swapchain_;
  pi.pImageIndices = &index;
  r = vkQueuePresentKHR(device_.queue(), &pi);
  if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) {
    vkDeviceWaitIdle(dev);
    engine::vk_check(vkWaitForFences(dev, 1, &done_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    engine::vk_check(vkResetFences(dev, 1, &done_), "vkResetFences");
    submitted_ = false;
    destroy_swapchain();
    create_swapchain();
    return;
  }
  engine::vk_check(r, "vkQueuePresentKHR");
}

}  // namespace tressvk::viewer
