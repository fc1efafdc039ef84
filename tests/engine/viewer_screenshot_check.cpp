// Checks that a tressvk-viewer screenshot shows hair: it renders the same scene headlessly with the demo's frame
// (DemoApp, the code the viewer runs) for the same number of frames with the hair left out, and counts the pixels
// where the screenshot differs. An empty window, a frame without hair or a wrong scene fails.
// Usage: tressvk_viewer_screenshot_check SCREENSHOT.png FRAMES
#include "demo_app.hpp"

#include <tressvk/engine/device.hpp>
#include <tressvk/engine/png.hpp>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

int main(int argc, char** argv) {
  using namespace tressvk;
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s SCREENSHOT.png FRAMES\n", argv[0]);
    return 2;
  }
  try {
    const engine::Pixels shot = engine::read_png(argv[1]);
    const auto frames = static_cast<uint32_t>(std::stoul(argv[2]));
    engine::DeviceOptions device_options;
    device_options.validation = true;
    device_options.sync_validation = true;
    engine::Device device(host::with_plugin_requirements(device_options));
    demo::Options options;
    options.width = shot.width;
    options.height = shot.height;
    options.draw_hair = false;
    engine::Pixels bare;
    {
      demo::DemoApp app(device, options);
      app.run(frames, [&](demo::FrameReport& f) { bare = std::move(f.pixels); });
    }
    // Threshold 24 of 255 per channel: hair over skin or background changes a pixel by far more; lavapipe's
    // rasterization of the same meshes is deterministic, so the bare frame and the screenshot agree elsewhere.
    const engine::PixelDiff d = engine::compare_rgba8(shot, bare, 24);
    std::printf("screenshot %ux%u: %.1f %% of the pixels are hair (differ from the same frame without hair)\n",
                shot.width, shot.height, 100.0 * d.fraction_over);
    // The bundled head's groom covers the top and back of the head and the shoulders: well over 3 % of the frame.
    if (d.fraction_over < 0.03) {
      std::fprintf(stderr, "the screenshot shows no hair (%.2f %% of the pixels differ from the frame without it)\n",
                   100.0 * d.fraction_over);
      return 1;
    }
    if (device.messages().count() != 0) {
      std::fprintf(stderr, "validation messages in the reference render\n");
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
