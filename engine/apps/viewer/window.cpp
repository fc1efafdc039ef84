#include "window.hpp"

#include <tressvk/engine/check.hpp>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>

namespace tressvk::viewer {

namespace {

Window& self(GLFWwindow* w) { return *static_cast<Window*>(glfwGetWindowUserPointer(w)); }

std::string glfw_error() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description ? description : "unknown GLFW error";
}

}  // namespace

Window::Window(uint32_t width, uint32_t height, const std::string& title) {
  if (!glfwInit())
    throw engine::Error("cannot open a window: " + glfw_error() + " (is DISPLAY set? Without a screen: xvfb-run)");
  if (!glfwVulkanSupported()) {
    glfwTerminate();
    throw engine::Error("cannot open a window: GLFW found no Vulkan loader with window-system support");
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);  // the frame is rendered at the window's size
  window_ = glfwCreateWindow(static_cast<int>(width), static_cast<int>(height), title.c_str(), nullptr, nullptr);
  if (!window_) {
    const std::string reason = glfw_error();
    glfwTerminate();
    throw engine::Error("cannot open a window: " + reason);
  }
  glfwSetWindowUserPointer(window_, this);
  glfwSetKeyCallback(window_, on_key);
  glfwSetMouseButtonCallback(window_, on_button);
  glfwSetCursorPosCallback(window_, on_cursor);
  glfwSetScrollCallback(window_, on_scroll);
  glfwSetDropCallback(window_, on_drop);
}

Window::~Window() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

std::vector<std::string> Window::instance_extensions() const {
  uint32_t n = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&n);
  if (!names) throw engine::Error("GLFW knows no Vulkan surface extension for this window system");
  return std::vector<std::string>(names, names + n);
}

VkSurfaceKHR Window::create_surface(VkInstance instance) const {
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  engine::vk_check(glfwCreateWindowSurface(instance, window_, nullptr, &surface), "glfwCreateWindowSurface");
  return surface;
}

void Window::framebuffer_size(uint32_t& width, uint32_t& height) const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  width = static_cast<uint32_t>(std::max(w, 1));
  height = static_cast<uint32_t>(std::max(h, 1));
}

void Window::set_title(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }

bool Window::poll() {
  glfwPollEvents();
  return !glfwWindowShouldClose(window_);
}

void Window::on_key(GLFWwindow* w, int key, int, int action, int) {
  if (action != GLFW_PRESS) return;
  Window& s = self(w);
  if (s.ui_has_keyboard) return;
  switch (key) {
    case GLFW_KEY_SPACE: s.view.paused = !s.view.paused; break;
    case GLFW_KEY_R: s.reset_requested = true; break;
    case GLFW_KEY_P: s.save_requested = true; break;
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q: glfwSetWindowShouldClose(w, GLFW_TRUE); break;
    default: break;
  }
}

void Window::on_button(GLFWwindow* w, int button, int action, int) {
  Window& s = self(w);
  if (button != GLFW_MOUSE_BUTTON_LEFT) return;
  s.dragging_ = action == GLFW_PRESS && !s.ui_has_mouse;
  glfwGetCursorPos(w, &s.last_x_, &s.last_y_);
}

void Window::on_cursor(GLFWwindow* w, double x, double y) {
  Window& s = self(w);
  if (s.dragging_) {
    constexpr double kRadiansPerPixel = 0.008;
    s.view.yaw -= (x - s.last_x_) * kRadiansPerPixel;
    s.view.pitch = std::clamp(s.view.pitch + (y - s.last_y_) * kRadiansPerPixel, -1.4, 1.4);
  }
  s.last_x_ = x;
  s.last_y_ = y;
}

void Window::on_scroll(GLFWwindow* w, double, double dy) {
  Window& s = self(w);
  if (s.ui_has_mouse) return;
  s.view.zoom = std::clamp(s.view.zoom * (dy > 0 ? 0.9 : 1.0 / 0.9), 0.25, 4.0);
}

void Window::on_drop(GLFWwindow* w, int count, const char** paths) {
  Window& s = self(w);
  for (int i = 0; i < count; ++i) s.dropped.emplace_back(paths[i]);
}

}  // namespace tressvk::viewer
