// The viewer's Dear ImGui panel (Debian libimgui-dev, its GLFW and Vulkan backends): simulation parameters,
// material, wind, LOD, the plugin's per-pass GPU times and the demo frame's pass times, play/pause and reset, and
// saving or loading the JSON parameter file that tressvk-demo --params reads.
#pragma once

#include "demo_app.hpp"
#include "presenter.hpp"
#include "window.hpp"

#include <tressvk/engine/device.hpp>

#include <string>

namespace tressvk::viewer {

class Panel {
 public:
  Panel(engine::Device& device, Window& window, const Presenter& presenter);
  ~Panel();
  Panel(const Panel&) = delete;
  Panel& operator=(const Panel&) = delete;

  // Builds this frame's panel for app (edits go to it at once) and the last frame's report.
  void build(demo::DemoApp& app, const demo::FrameReport& frame, Window& window);
  // Records the panel's draws (inside Presenter::render_pass()).
  void record(VkCommandBuffer cmd);

  std::string message;           // shown in red at the top: the last error (bad file, bad parameter file)
  std::string params_path = "viewer-params.json";

 private:
  engine::Device& device_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  bool built_ = false;
};

}  // namespace tressvk::viewer
