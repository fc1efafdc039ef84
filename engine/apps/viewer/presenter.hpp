// The viewer's swapchain: each rendered frame (the demo frame's pixels, as tressvk-demo writes them to PNG) is
// copied into the next swapchain image and presented. One frame at a time: the copy of frame n finishes before
// frame n+1 is staged, which costs nothing next to the rendering and keeps the synchronization obvious.
#pragma once

#include <tressvk/engine/buffer.hpp>
#include <tressvk/engine/device.hpp>
#include <tressvk/engine/image.hpp>

#include <volk.h>

#include <cstdint>
#include <functional>
#include <vector>

namespace tressvk::viewer {

class Presenter {
 public:
  // device must have been made with a surface (DeviceOptions::create_surface). width x height: the window's
  // framebuffer size in pixels, used when the surface leaves the extent to the swapchain.
  Presenter(engine::Device& device, uint32_t width, uint32_t height);
  ~Presenter();
  Presenter(const Presenter&) = delete;
  Presenter& operator=(const Presenter&) = delete;

  // Shows pixels (8-bit RGBA, sRGB-encoded) in the window; a smaller or larger swapchain gets the overlap.
  // overlay, if given, records draws (the ImGui panel) into render_pass() over the frame.
  void present(const engine::Pixels& pixels, const std::function<void(VkCommandBuffer)>& overlay = {});

  // The pass the overlay draws in: the swapchain image, loaded (the frame), then presented.
  VkRenderPass render_pass() const { return render_pass_; }
  uint32_t image_count() const { return static_cast<uint32_t>(images_.size()); }

 private:
  void create_swapchain();
  void destroy_swapchain();

  engine::Device& device_;
  uint32_t width_, height_;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  bool bgra_ = false;  // swapchain stores B, G, R, A: swizzle while staging
  VkExtent2D extent_{};
  std::vector<VkImage> images_;
  std::vector<VkImageView> views_;
  std::vector<VkFramebuffer> framebuffers_;
  VkRenderPass render_pass_ = VK_NULL_HANDLE;
  std::vector<VkSemaphore> ready_to_present_;  // one per swapchain image
  VkSemaphore acquired_ = VK_NULL_HANDLE;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence done_ = VK_NULL_HANDLE;
  bool submitted_ = false;
  engine::Buffer staging_;
};

}  // namespace tressvk::viewer
