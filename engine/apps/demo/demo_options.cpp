#include "demo_options.hpp"

#include <CLI/CLI.hpp>

namespace tressvk::demo {

int parse_options(int argc, char** argv, Options& options) {
  CLI::App app{"tressvk-demo: renders frames offscreen with the TressVK plugin and writes them as PNG files"};
  app.add_option("--frames", options.frames, "Number of frames to render")->check(CLI::Range(1u, 100000u));
  app.add_option("--out", options.out_dir, "Output directory for frame_NNNN.png")->capture_default_str();
  app.add_option("--width", options.width, "Frame width in pixels")->check(CLI::Range(16u, 8192u))
      ->capture_default_str();
  app.add_option("--height", options.height, "Frame height in pixels")->check(CLI::Range(16u, 8192u))
      ->capture_default_str();
  app.add_option("--device", options.device,
                 "Vulkan device: index or name substring (default: TRESSVK_DEVICE, else discrete GPU first)");
  app.add_flag("--validation", options.validation,
               "Enable the Vulkan validation layer with synchronization validation; any message fails the run");
  app.add_flag("--list-devices", options.list_devices, "List the Vulkan devices and exit");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  return -1;
}

}  // namespace tressvk::demo
