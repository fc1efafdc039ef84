#include <tressvk/engine/buffer.hpp>
#include <tressvk/engine/image.hpp>

#include <string>
#include <utility>
#include <vector>

namespace tressvk::engine {

bool is_depth_format(VkFormat format) {
  switch (format) {
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_X8_D24_UNORM_PACK32:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_D16_UNORM_S8_UINT:
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
      return true;
    default:
      return false;
  }
}

uint32_t format_texel_size(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_B8G8R8A8_SRGB:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_D32_SFLOAT:
      return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
      return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      return 16;
    default:
      return 0;
  }
}

Image::Image(const Device& device, const ImageDesc& desc)
    : device_(device.device()), allocator_(device.allocator()), desc_(desc) {
  if (desc.width == 0 || desc.height == 0) throw Error("Image: width and height must be positive");
  aspect_ = is_depth_format(desc.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
  VkImageCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = desc.format;
  info.extent = {desc.width, desc.height, 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = desc.samples;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = desc.usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VmaAllocationCreateInfo aci{};
  aci.usage = VMA_MEMORY_USAGE_AUTO_PREFER_DEVICE;
  vk_check(vmaCreateImage(allocator_, &info, &aci, &image_, &allocation_, nullptr), "vmaCreateImage");

  VkImageViewCreateInfo vi{};

  vi.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
  vi.image = image_;
  vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vi.format = desc.format;
  vi.subresourceRange = {aspect_, 0, 1, 0, 1};
  const VkResult vr = vkCreateImageView(device_, &vi, nullptr, &view_);
  if (vr != VK_SUCCESS) {
    reset();
    vk_check(vr, "vkCreateImageView");
  }
}

Image::Image(Image&& other) noexcept { *this = std::move(other); }

Image& Image::operator=(Image&& other) noexcept {
  if (this != &other) {
    reset();
    device_ = other.device_;
    allocator_ = other.allocator_;
    image_ = std::exchange(other.image_, VK_NULL_HANDLE);
    allocation_ = std::exchange(other.allocation_, VK_NULL_HANDLE);
    view_ = std::exchange(other.view_, VK_NULL_HANDLE);
    desc_ = other.desc_;
    aspect_ = other.aspect_;
  }
  return *this;
}

void Image::reset() {
  if (view_) vkDestroyImageView(device_, view_, nullptr);
  if (image_) vmaDestroyImage(allocator_, image_, allocation_);
  view_ = VK_NULL_HANDLE;
  image_ = VK_NULL_HANDLE;
  allocation_ = VK_NULL_HANDLE;
}

OffscreenTarget create_offscreen_target(const Device& device, uint32_t width, uint32_t height, VkFormat color_format,
                                        VkFormat depth_format) {
  OffscreenTarget target;
  if (color_format != VK_FORMAT_UNDEFINED)
    target.color = Image(device, {width, height, color_format,
                                  VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                      VK_IMAGE_USAGE_SAMPLED_BIT});
  if (depth_format != VK_FORMAT_UNDEFINED)
    target.depth = Image(device, {width, height, depth_format,
                                  VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                      VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT});
  return target;
}

void cmd_set_viewport_scissor(VkCommandBuffer cmd, VkExtent2D extent) {
  const VkViewport viewport{0.0f, 0.0f, static_cast<float>(extent.width), static_cast<float>(extent.height),
                            0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, extent};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void cmd_begin_rendering(VkCommandBuffer cmd, const OffscreenTarget& target, const ClearValues& clear,
                         const ResourceState& previous_color, const ResourceState& previous_depth, bool load) {
  VkRenderingAttachmentInfo color{};
  color.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
  VkRenderingAttachmentInfo depth{};
  depth.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
  VkRenderingInfo info{};
  info.sType = VK_STRUCTURE_TYPE_RENDERING_INFO;
  info.renderArea = {{0, 0}, target.extent()};
  info.layerCount = 1;
  // Moves the image into `next` and points the attachment at it, loaded or cleared, always stored.
  const auto attach = [&](VkRenderingAttachmentInfo& a, const Image& image, VkImageAspectFlags aspect,
                          const ResourceState& previous, const ResourceState& next) {
    cmd_image_barrier(cmd, image.handle(), aspect, previous, next);
    a.imageView = image.view();
    a.imageLayout = next.layout;
    a.loadOp = load ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  };
  if (target.color) {
    attach(color, target.color, VK_IMAGE_ASPECT_COLOR_BIT, previous_color, state::kColorAttachment);
    for (int i = 0; i < 4; ++i) color.clearValue.color.float32[i] = clear.color[static_cast<size_t>(i)];
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &color;
  }
  if (target.depth) {
    attach(depth, target.depth, VK_IMAGE_ASPECT_DEPTH_BIT, previous_depth, state::kDepthAttachment);
    depth.clearValue.depthStencil = {clear.depth, 0};
    info.pDepthAttachment = &depth;
  }
  vkCmdBeginRendering(cmd, &info);
  cmd_set_viewport_scissor(cmd, target.extent());
}

void cmd_end_rendering(VkCommandBuffer cmd) { vkCmdEndRendering(cmd); }

RenderPassTarget::RenderPassTarget(const Device& device, const OffscreenTarget& target)
    : RenderPassTarget(device, target, false) {}

RenderPassTarget::RenderPassTarget(const Device& device, const OffscreenTarget& target, bool load)
    : extent_(target.extent()), has_color_(static_cast<bool>(target.color)), has_depth_(static_cast<bool>(target.depth)) {
  std::vector<VkAttachmentDescription> attachments;
  std::vector<VkImageView> views;
  VkAttachmentReference color_ref{VK_ATTACHMENT_UNUSED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkAttachmentReference depth_ref{VK_ATTACHMENT_UNUSED, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  auto add = [&](const Image& image, VkImageLayout layout, VkAttachmentReference& ref) {
    VkAttachmentDescription a{};
    a.format = image.format();
    a.samples = VK_SAMPLE_COUNT_1_BIT;
    a.loadOp = load ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a.initialLayout = load ? layout : VK_IMAGE_LAYOUT_UNDEFINED;
    a.finalLayout = layout;
    ref.attachment = static_cast<uint32_t>(attachments.size());
    attachments.push_back(a);
    views.push_back(image.view());
  };
  if (target.color) add(target.color, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, color_ref);
  if (target.depth) add(target.depth, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, depth_ref);

  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = target.color ? 1 : 0;
  subpass.pColorAttachments = target.color ? &color_ref : nullptr;
  subpass.pDepthStencilAttachment = target.depth ? &depth_ref : nullptr;

  // Conservative external dependencies: a host pass is a boundary, so it waits for everything before it and
  // makes its attachment writes available to everything after it.
  const VkPipelineStageFlags attachment_stages = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                                 VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                                 VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  const VkAccessFlags attachment_access =
      VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
      VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  VkSubpassDependency deps[2]{};
  deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  deps[0].dstSubpass = 0;
  deps[0].srcStageMask = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT;
  deps[0].srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  deps[0].dstStageMask = attachment_stages;
  deps[0].dstAccessMask = attachment_access;
  deps[1].srcSubpass = 0;
  deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  deps[1].srcStageMask = attachment_stages;
  deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  deps[1].dstStageMask = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT;
  deps[1].dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;

  VkRenderPassCreateInfo rpci{};
  rpci.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
  rpci.attachmentCount = static_cast<uint32_t>(attachments.size());
  rpci.pAttachments = attachments.data();
  rpci.subpassCount = 1;
  rpci.pSubpasses = &subpass;
  rpci.dependencyCount = 2;
  rpci.pDependencies = deps;
  VkRenderPass render_pass = VK_NULL_HANDLE;
  vk_check(vkCreateRenderPass(device.device(), &rpci, nullptr, &render_pass), "vkCreateRenderPass");
  render_pass_ = DeviceHandle<VkRenderPass>(device.device(), render_pass, vkDestroyRenderPass);

  VkFramebufferCreateInfo fci{};
  fci.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
  fci.renderPass = render_pass;
  fci.attachmentCount = static_cast<uint32_t>(views.size());
  fci.pAttachments = views.data();
  fci.width = extent_.width;
  fci.height = extent_.height;
  fci.layers = 1;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  vk_check(vkCreateFramebuffer(device.device(), &fci, nullptr, &framebuffer), "vkCreateFramebuffer");
  framebuffer_ = DeviceHandle<VkFramebuffer>(device.device(), framebuffer, vkDestroyFramebuffer);
}

void cmd_begin_render_pass(VkCommandBuffer cmd, const RenderPassTarget& target, const ClearValues& clear) {
  VkClearValue values[2]{};
  uint32_t n = 0;
  if (target.has_color()) {
    for (int i = 0; i < 4; ++i) values[n].color.float32[i] = clear.color[static_cast<size_t>(i)];
    ++n;
  }
  if (target.has_depth()) values[n++].depthStencil = {clear.depth, 0};
  VkRenderPassBeginInfo info{};
  info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
  info.renderPass = target.render_pass();
  info.framebuffer = target.framebuffer();
  info.renderArea = {{0, 0}, target.extent()};
  info.clearValueCount = n;
  info.pClearValues = values;
  vkCmdBeginRenderPass(cmd, &info, VK_SUBPASS_CONTENTS_INLINE);
  cmd_set_viewport_scissor(cmd, target.extent());
}

void cmd_end_render_pass(VkCommandBuffer cmd) { vkCmdEndRenderPass(cmd); }

std::array<uint8_t, 4> Pixels::rgba8(uint32_t x, uint32_t y) const {
  if (x >= width || y >= height || texel_size != 4) throw Error("Pixels::rgba8: out of range or not 8-bit RGBA");
  const size_t i = (static_cast<size_t>(y) * width + x) * 4;
  return {data[i], data[i + 1], data[i + 2], data[i + 3]};
}

namespace {
uint32_t readback_texel_size(const Image& image) {
  const uint32_t texel = format_texel_size(image.format());
  // Of the depth formats only D32_SFLOAT copies out as plain floats; packed D24 and stencil formats do not.
  if (texel == 0 || (is_depth_format(image.format()) && image.format() != VK_FORMAT_D32_SFLOAT))
    throw Error("image readback: format " + std::to_string(image.format()) + " is not supported");
  return texel;
}
}  // namespace

void cmd_readback_image(VkCommandBuffer cmd, const Image& image, const ResourceState& current, const Buffer& buffer) {
  const VkDeviceSize bytes = VkDeviceSize{readback_texel_size(image)} * image.width() * image.height();
  if (buffer.size() < bytes || !buffer.mapped())
    throw Error("image readback: the buffer must be a mapped readback buffer of at least " + std::to_string(bytes) +
                " bytes");
  cmd_image_barrier(cmd, image.handle(), image.aspect(), current, state::kTransferSrc);
  VkBufferImageCopy region{};
  region.bufferRowLength = 0;  // tightly packed
  region.imageSubresource = {image.aspect(), 0, 0, 1};
  region.imageExtent = {image.width(), image.height(), 1};
  vkCmdCopyImageToBuffer(cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer.handle(), 1, &region);
  cmd_buffer_barrier(cmd, buffer.handle(), state::kTransferDst, state::kHostRead);
}

Pixels pixels_from_buffer(const Buffer& buffer, const Image& image) {
  Pixels pixels;
  pixels.width = image.width();
  pixels.height = image.height();
  pixels.texel_size = readback_texel_size(image);
  const VkDeviceSize bytes = VkDeviceSize{pixels.texel_size} * image.width() * image.height();
  if (buffer.size() < bytes || !buffer.mapped()) throw Error("pixels_from_buffer: buffer too small or not mapped");
  vk_check(vmaInvalidateAllocation(buffer.allocator(), buffer.allocation(), 0, bytes), "vmaInvalidateAllocation");
  pixels.data.resize(static_cast<size_t>(bytes));
  std::memcpy(pixels.data.data(), buffer.mapped(), pixels.data.size());
  return pixels;
}

float Pixels::r32f(uint32_t x, uint32_t y) const {
  if (x >= width || y >= height || texel_size != 4) throw Error("Pixels::r32f: out of range or not 32-bit");
  float value = 0.0f;
  std::memcpy(&value, data.data() + (static_cast<size_t>(y) * width + x) * 4, sizeof(float));
  return value;
}

Pixels read_image(const Device& device, const Image& image, const ResourceState& current) {
  const VkDeviceSize bytes = VkDeviceSize{readback_texel_size(image)} * image.width() * image.height();
  Buffer staging = create_buffer(device, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::readback);
  device.run_commands([&](VkCommandBuffer cmd) {
    cmd_readback_image(cmd, image, current, staging);
    // Back to the caller's layout; later users wait for the copy's read.
    if (current.layout != VK_IMAGE_LAYOUT_UNDEFINED)
      cmd_image_barrier(cmd, image.handle(), image.aspect(), state::kTransferSrc, current);
  });
  return pixels_from_buffer(staging, image);
}

}  // namespace tressvk::engine
