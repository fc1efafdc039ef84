// The viewer's window (GLFW): the Vulkan surface for the engine's device, and the input a person uses to look at
// hair: left-drag orbits, the wheel zooms, space pauses, R resets, P saves the parameters, Esc/Q quits, and files
// dropped on the window are queued for loading.
#pragma once

#include "demo_app.hpp"

#include <volk.h>

#include <cstdint>
#include <string>
#include <vector>

struct GLFWwindow;

namespace tressvk::viewer {

class Window {
 public:
  // Throws engine::Error with the reason when there is no display or GLFW has no Vulkan.
  Window(uint32_t width, uint32_t height, const std::string& title);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  std::vector<std::string> instance_extensions() const;  // what the surface needs (xcb/xlib/wayland...)
  VkSurfaceKHR create_surface(VkInstance instance) const;
  void framebuffer_size(uint32_t& width, uint32_t& height) const;
  void set_title(const std::string& title);
  GLFWwindow* handle() const { return window_; }

  // Processes pending events; false once the window was asked to close.
  bool poll();

  demo::ViewControl view;          // orbit, zoom and pause as the input left them
  bool reset_requested = false;    // R: camera and animation back to the start
  bool save_requested = false;     // P: write the parameters in effect
  std::vector<std::string> dropped;  // paths dropped on the window, oldest first
  bool ui_has_mouse = false;         // the panel is under the mouse: no orbit or zoom
  bool ui_has_keyboard = false;      // the panel takes the keys (a text field): no shortcuts

 private:
  static void on_key(GLFWwindow* w, int key, int scancode, int action, int mods);
  static void on_button(GLFWwindow* w, int button, int action, int mods);
  static void on_cursor(GLFWwindow* w, double x, double y);
  static void on_scroll(GLFWwindow* w, double dx, double dy);
  static void on_drop(GLFWwindow* w, int count, const char** paths);

  GLFWwindow* window_ = nullptr;
  bool dragging_ = false;
  double last_x_ = 0.0, last_y_ = 0.0;
};

}  // namespace tressvk::viewer
