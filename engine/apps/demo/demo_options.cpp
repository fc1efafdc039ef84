#include "demo_options.hpp"

#include <CLI/CLI.hpp>

#include <map>
#include <vector>

namespace tressvk::demo {

const char* animation_name(Animation a) {
  switch (a) {
    case Animation::none: return "none";
    case Animation::turn: return "turn";
    case Animation::shake: return "shake";
    case Animation::run: return "run";
  }
  return "?";
}

int parse_options(int argc, char** argv, Options& options) {
  CLI::App app{"tressvk-demo: renders a head of simulated hair offscreen with the TressVK plugin and writes the "
               "frames as PNG files"};
  app.add_option("--frames", options.frames, "Number of frames to render (60 per simulated second)")
      ->check(CLI::Range(1u, 100000u));
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
  app.add_option("--asset", options.asset, "A baked .tvkhair asset (default: the bundled procedural groom)")
      ->check(CLI::ExistingFile);
  app.add_option("--mesh", options.mesh, "An OBJ head or character mesh in metres, in the asset's space")
      ->check(CLI::ExistingFile);
  app.add_option("--mesh-scale", options.mesh_scale,
                 "Uniform scale from the OBJ's units to metres (bake the hair with the same tressvk-bake --scale)")
      ->check(CLI::PositiveNumber)->capture_default_str();
  const std::map<std::string, Animation> animations{
      {"none", Animation::none}, {"turn", Animation::turn}, {"shake", Animation::shake}, {"run", Animation::run}};
  app.add_option("--animate", options.animate, "Head motion: none, turn, shake or run")
      ->transform(CLI::CheckedTransformer(animations, CLI::ignore_case))
      ->default_str("turn");
  app.add_option("--wind", options.wind, "Wind strength in m/s^2 (0 = none)")->check(CLI::Range(0.0f, 1000.0f));
  const std::map<std::string, HairPath> paths{{"compute", HairPath::compute}, {"raster", HairPath::raster}};
  app.add_option("--path", options.hair_path,
                 "Hair renderer: compute (strand rasterizer, sorted per tile) or raster (quads in the main pass)")
      ->transform(CLI::CheckedTransformer(paths, CLI::ignore_case))
      ->default_str("compute");
  bool no_shadows = false;
  app.add_flag("--no-shadows", no_shadows, "Render without the shadow map (no hair or mesh shadows)");
  app.add_option("--camera-distance", options.camera_distance, "Camera distance in metres (0 = frame the scene)")
      ->check(CLI::Range(0.0f, 100000.0f));
  app.add_option("--lod-start", options.lod_start, "Hair LOD: distance in metres where thinning starts (0 = off)")
      ->check(CLI::Range(0.0f, 100000.0f));
  app.add_option("--lod-end", options.lod_end, "Hair LOD: distance in metres of the fewest strands")
      ->check(CLI::Range(0.0f, 100000.0f));
  app.add_option("--lod-min-fraction", options.lod_min_fraction, "Hair LOD: fraction of strands drawn at --lod-end")
      ->check(CLI::Range(0.01f, 1.0f))->capture_default_str();
  app.add_option("--guides", options.guides, "Bundled groom: guide strands")->check(CLI::Range(16u, 100000u))
      ->capture_default_str();
  app.add_option("--follows", options.follows, "Bundled groom: follow strands per guide")
      ->check(CLI::Range(0u, 16u))->capture_default_str();
  std::vector<double> offset;
  app.add_option("--world-offset", offset, "X Y Z: place the whole scene this far from the world origin (metres)")
      ->expected(3);
  try {
    app.parse(argc, argv);
    if (offset.size() == 3) options.world_offset = {offset[0], offset[1], offset[2]};
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  options.shadows = !no_shadows;
  return -1;
}

}  // namespace tressvk::demo
