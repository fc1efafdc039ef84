// RAII 2D images with one view, allocated with VMA; offscreen colour + depth targets; readback to the CPU.
#pragma once

#include <tressvk/engine/device.hpp>
#include <tressvk/engine/handle.hpp>
#include <tressvk/engine/sync.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace tressvk::engine {

struct ImageDesc {
  uint32_t width = 1;
  uint32_t height = 1;
  VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
  VkImageUsageFlags usage = 0;
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
};

class Image {
 public:
  Image() = default;
  Image(const Device& device, const ImageDesc& desc);
  ~Image() { reset(); }
  Image(Image&& other) noexcept;
  Image& operator=(Image&& other) noexcept;
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;

  VkImage handle() const { return image_; }
  VkImageView view() const { return view_; }
  VkFormat format() const { return desc_.format; }
  VkImageAspectFlags aspect() const { return aspect_; }
  uint32_t width() const { return desc_.width; }
  uint32_t height() const { return desc_.height; }
  VkExtent2D extent() const { return {desc_.width, desc_.height}; }
  explicit operator bool() const { return image_ != VK_NULL_HANDLE; }
  void reset();

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  VmaAllocator allocator_ = VK_NULL_HANDLE;
  VkImage image_ = VK_NULL_HANDLE;
  VmaAllocation allocation_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  ImageDesc desc_{};
  VkImageAspectFlags aspect_ = 0;
};

bool is_depth_format(VkFormat format);
// Bytes per texel for the formats the engine reads back (8-bit RGBA/BGRA, R32 float, D32); 0 otherwise.
uint32_t format_texel_size(VkFormat format);

// An offscreen colour + depth target for dynamic rendering. Colour can be sampled and copied (readback); depth
// can be sampled (a shadow map is a depth-only target).
struct OffscreenTarget {
  Image color;
  Image depth;
  VkExtent2D extent() const { return color ? color.extent() : depth.extent(); }
};

// color_format VK_FORMAT_UNDEFINED gives a depth-only target; depth_format VK_FORMAT_UNDEFINED a colour-only one.
OffscreenTarget create_offscreen_target(const Device& device, uint32_t width, uint32_t height,
                                        VkFormat color_format = VK_FORMAT_R8G8B8A8_UNORM,
                                        VkFormat depth_format = VK_FORMAT_D32_SFLOAT);

struct ClearValues {
  std::array<float, 4> color{0.0f, 0.0f, 0.0f, 1.0f};
  float depth = 1.0f;
};

// Transitions the target from `previous` (per attachment; kUndefined discards the old contents) to attachment
// layouts, begins dynamic rendering with clears (or, with `load`, keeping the contents: `previous` must then
// name their real layouts), and sets a full-target viewport and scissor.
void cmd_begin_rendering(VkCommandBuffer cmd, const OffscreenTarget& target, const ClearValues& clear,
                         const ResourceState& previous_color = state::kUndefined,
                         const ResourceState& previous_depth = state::kUndefined, bool load = false);
void cmd_end_rendering(VkCommandBuffer cmd);

// The same target through a classic VkRenderPass + VkFramebuffer (one subpass), for hosts that do not use
// dynamic rendering; the plugin must draw into both. The pass clears both attachments (their old contents are
// discarded), waits for all earlier commands, and leaves colour in COLOR_ATTACHMENT_OPTIMAL (state
// kColorAttachment) and depth in DEPTH_STENCIL_ATTACHMENT_OPTIMAL, with its writes made available to all later
// commands.
class RenderPassTarget {
 public:
  RenderPassTarget() = default;
  RenderPassTarget(const Device& device, const OffscreenTarget& target);
  // With `load`: a pass that keeps the attachments' contents (LOAD ops), entered with colour in
  // COLOR_ATTACHMENT_OPTIMAL and depth in DEPTH_STENCIL_ATTACHMENT_OPTIMAL (a second pass on the same target,
  // compatible with the clearing one, so the same pipelines draw in both).
  RenderPassTarget(const Device& device, const OffscreenTarget& target, bool load);
  VkRenderPass render_pass() const { return render_pass_.get(); }
  VkFramebuffer framebuffer() const { return framebuffer_.get(); }
  VkExtent2D extent() const { return extent_; }
  bool has_color() const { return has_color_; }
  bool has_depth() const { return has_depth_; }

 private:
  DeviceHandle<VkRenderPass> render_pass_;
  DeviceHandle<VkFramebuffer> framebuffer_;
  VkExtent2D extent_{};
  bool has_color_ = false;
  bool has_depth_ = false;
};
// Begins the render pass with clears and sets a full-target viewport and scissor.
void cmd_begin_render_pass(VkCommandBuffer cmd, const RenderPassTarget& target, const ClearValues& clear);
void cmd_end_render_pass(VkCommandBuffer cmd);
void cmd_set_viewport_scissor(VkCommandBuffer cmd, VkExtent2D extent);

// Tightly packed pixels read back from a colour image (row-major, top row first).
struct Pixels {
  uint32_t width = 0;
  uint32_t height = 0;
  uint32_t texel_size = 0;  // bytes per pixel
  std::vector<uint8_t> data;
  // 8-bit RGBA (or BGRA as stored) pixel at (x, y).
  std::array<uint8_t, 4> rgba8(uint32_t x, uint32_t y) const;
  // 32-bit float texel (R32_SFLOAT colour or D32_SFLOAT depth) at (x, y).
  float r32f(uint32_t x, uint32_t y) const;
};

// Copies an image in state `current` to the CPU (waits): 8-bit RGBA/BGRA, float colour, or D32_SFLOAT depth
// (e.g. a shadow map). The image is left in `current`'s layout.
Pixels read_image(const Device& device, const Image& image, const ResourceState& current);

class Buffer;
// The recording half of a readback, for frames in flight: transitions the image from `current` to
// kTransferSrc (where it stays), copies it tightly packed into `buffer` (a MemoryUsage::readback buffer of at
// least texel size * width * height bytes) and makes the copy visible to the host. After the submission has
// finished, pixels_from_buffer() gives the pixels.
void cmd_readback_image(VkCommandBuffer cmd, const Image& image, const ResourceState& current, const Buffer& buffer);
Pixels pixels_from_buffer(const Buffer& buffer, const Image& image);

}  // namespace tressvk::engine
