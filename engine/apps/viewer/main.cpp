// tressvk-viewer: the demo's scene in a window. The same engine device (with a window surface), the same scene,
// plugin calls and frame as tressvk-demo (DemoApp); each finished frame is presented through the swapchain.
// Bad input (a missing or broken file on the command line, a parameter file that does not parse) stops with a
// message naming the file and exit code 2; a bad file dropped on the window is reported and the current hair stays.
#include "demo_app.hpp"
#include "panel.hpp"
#include "params.hpp"
#include "presenter.hpp"
#include "viewer_options.hpp"
#include "window.hpp"

#include <tressvk/engine/device.hpp>
#include <tressvk/engine/png.hpp>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

namespace {

using namespace tressvk;

// The input could not be used: its message names the file.
struct BadInput : std::runtime_error {
  using std::runtime_error::runtime_error;
};

demo::Options scene_options(const viewer::ViewerOptions& options, const std::string& file, uint32_t width,
                            uint32_t height) {
  demo::Options o;
  o.asset = file;
  o.width = width;
  o.height = height;
  o.mesh = options.mesh;
  o.mesh_scale = options.mesh_scale;
  o.params_file = options.params_file;
  o.pass_timings = true;  // the panel shows the plugin's per-pass GPU times
  o.step_error = true;    // and the step error against the reference on request
  o.validation = options.validation;
  return o;
}

// Loads a scene; a file that is missing or does not load is BadInput (the message names it).
std::unique_ptr<demo::DemoApp> load(engine::Device& device, const demo::Options& o) {
  if (!o.asset.empty() && !std::filesystem::is_regular_file(o.asset))
    throw BadInput(o.asset + ": no such file (give a .tvkhair asset, a TressFX .tfx or an OBJ with hair curves)");
  try {
    return std::make_unique<demo::DemoApp>(device, o);
  } catch (const engine::VulkanError&) {
    throw;  // the device's fault, not the file's
  } catch (const std::exception& e) {
    const std::string what = e.what();
    const std::string& name = o.asset.empty() ? o.params_file : o.asset;
    throw BadInput(what.find(name) == std::string::npos || name.empty() ? name + ": " + what : what);
  }
}

std::string title(const demo::DemoApp& app, const demo::FrameReport* frame) {
  char text[512];
  const demo::ViewControl& v = app.view();
  if (frame && frame->simulation_ms && frame->shadow_ms && frame->shading_ms)
    std::snprintf(text, sizeof(text), "tressvk-viewer: %s, t %.2f s%s, GPU sim %.2f ms, shadow %.2f ms, shading %.2f ms",
                  app.scene().asset_name.c_str(), app.time(), v.paused ? " (paused)" : "", *frame->simulation_ms,
                  *frame->shadow_ms, *frame->shading_ms);
  else
    std::snprintf(text, sizeof(text), "tressvk-viewer: %s, t %.2f s%s", app.scene().asset_name.c_str(), app.time(),
                  v.paused ? " (paused)" : "");
  return text;
}

int run(const viewer::ViewerOptions& options) {
  viewer::Window window(options.width, options.height, "tressvk-viewer");
  uint32_t width = 0, height = 0;
  window.framebuffer_size(width, height);

  engine::DeviceOptions device_options;
  device_options.app_name = "tressvk-viewer";
  device_options.device = options.device;
  device_options.validation = options.validation;
  device_options.sync_validation = options.validation;
  device_options.instance_extensions = window.instance_extensions();
  device_options.create_surface = [&](VkInstance instance) { return window.create_surface(instance); };
  auto device = std::make_unique<engine::Device>(host::with_plugin_requirements(device_options));
  const auto messages = device->message_log();
  std::printf("device: %s%s\n", device->description().c_str(),
              options.validation ? " [validation + synchronization validation]" : "");

  int code = viewer::kExitOk;
  {
    viewer::Presenter presenter(*device, width, height);
    viewer::Panel panel(*device, window, presenter);
    std::string file = options.file;
    std::unique_ptr<demo::DemoApp> app = load(*device, scene_options(options, file, width, height));
    std::printf("hair: %s: %u strands\n", app->scene().asset_name.c_str(), app->asset_info().total_strands);
    std::optional<engine::Pixels> last;
    uint32_t submitted = 0, shown = 0;
    bool open = true;
    while (open && (options.frames == 0 || submitted < options.frames)) {
      bool reload = false;
      app->run_while(
          [&] {
            open = window.poll();
            if (!open || (options.frames != 0 && submitted >= options.frames)) return false;
            if (window.save_requested) {
              window.save_requested = false;
              demo::save_params("viewer-params.json", app->params());
              std::printf("parameters: %s\n", std::filesystem::absolute("viewer-params.json").c_str());
            }
            if (window.reset_requested || !window.dropped.empty()) return reload = true, false;
            app->set_view(window.view);
            if (options.step_error && options.frames >= 3 && submitted == options.frames / 2) app->request_step_error();
            ++submitted;
            return true;
          },
          [&](demo::FrameReport& frame) {
            panel.build(*app, frame, window);
            presenter.present(frame.pixels, [&](VkCommandBuffer cmd) { panel.record(cmd); });
            if (shown++ % 30 == 0) window.set_title(title(*app, &frame));
            last = std::move(frame.pixels);
          });
      if (!reload) break;
      std::string next = file;
      if (!window.dropped.empty()) {
        next = window.dropped.front();
        window.dropped.erase(window.dropped.begin());
      }
      if (window.reset_requested) window.view = demo::ViewControl{};
      window.reset_requested = false;
      app.reset();  // one scene on the device at a time
      try {
        app = load(*device, scene_options(options, next, width, height));
        file = next;
        panel.message.clear();
        std::printf("hair: %s: %u strands\n", app->scene().asset_name.c_str(), app->asset_info().total_strands);
      } catch (const BadInput& e) {
        // A bad drop keeps the hair that was showing (its file loaded before, so it loads again).
        std::fprintf(stderr, "tressvk-viewer: error: %s\n", e.what());
        panel.message = e.what();
        app = load(*device, scene_options(options, file, width, height));
      }
    }
    device->wait_idle();
    if (!options.screenshot.empty()) {
      if (!last) throw engine::Error("no frame was rendered, so there is no screenshot to write");
      engine::write_png(options.screenshot, *last);
      std::printf("screenshot: %s\n", std::filesystem::absolute(options.screenshot).c_str());
    }
    std::printf("frames: %u\n", shown);
    if (const auto e = app->step_error())
      std::printf("step error: %.3g of the median strand length (one frame against the double reference)\n", *e);
  }
  device.reset();  // destruction is validated too
  if (options.validation) {
    const uint64_t n = messages->count();
    std::printf("validation: %llu message(s)\n", static_cast<unsigned long long>(n));
    if (n != 0) code = viewer::kExitError;
  }
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  viewer::ViewerOptions options;
  if (const int code = viewer::parse_viewer_options(argc, argv, options); code >= 0) return code;
  try {
    // Known before any window opens: a missing hair file and a parameter file that does not parse.
    if (!options.file.empty() && !std::filesystem::is_regular_file(options.file))
      throw BadInput(options.file + ": no such file (give a .tvkhair asset, a TressFX .tfx or an OBJ with hair curves)");
    if (!options.params_file.empty()) {
      try {
        (void)demo::load_params(options.params_file);
      } catch (const std::exception& e) {
        throw BadInput(e.what());
      }
    }
    return run(options);
  } catch (const BadInput& e) {
    std::fprintf(stderr, "tressvk-viewer: error: %s\n", e.what());
    return viewer::kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tressvk-viewer: error: %s\n", e.what());
    return viewer::kExitError;
  }
}
