#include "viewer_options.hpp"

#include <CLI/CLI.hpp>

namespace tressvk::viewer {

int parse_viewer_options(int argc, char** argv, ViewerOptions& options) {
  CLI::App app{"tressvk-viewer: simulated hair in a window. Left-drag orbits, the wheel zooms, space pauses, R "
               "resets, P saves the parameters (viewer-params.json), Esc quits; drop a .tvkhair, .tfx or OBJ file "
               "on the window to load it.\nExit codes: 0 ok, 1 error, 2 a missing or broken input file."};
  app.add_option("file", options.file, ".tvkhair asset, TressFX .tfx or OBJ hair curves (baked in memory); default: "
                                       "the bundled head and groom");
  app.add_option("--frames", options.frames, "Quit after this many frames (0: when the window closes)");
  app.add_option("--screenshot", options.screenshot, "Write the last frame to this PNG on exit");
  app.add_option("--mesh", options.mesh, "An OBJ head or character mesh in the hair's space (as tressvk-demo --mesh)")
      ->check(CLI::ExistingFile);
  app.add_option("--mesh-scale", options.mesh_scale, "OBJ units to metres for --mesh and OBJ hair curves");
  app.add_option("--params", options.params_file, "JSON parameter file (as tressvk-demo --params reads)");
  app.add_option("--width", options.width, "Window width in pixels")->check(CLI::Range(64u, 8192u));
  app.add_option("--height", options.height, "Window height in pixels")->check(CLI::Range(64u, 8192u));
  app.add_option("--device", options.device, "Vulkan device: index or name substring");
  app.add_flag("--step-error", options.step_error,
               "With --frames: measure one frame's step error against the double reference and print it");
  app.add_flag("--validation", options.validation,
               "Enable the Vulkan validation layer with synchronization validation; any message fails the run");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  return -1;
}

}  // namespace tressvk::viewer
