#include "demo_options.hpp"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <map>
#include <vector>

namespace tressvk::demo {

const char* animation_name(Animation a) {
  switch (a) {
    case Animation::none: return "none";
    case Animation::turn: return "turn";
    case Animation::shake: return "shake";
    case Animation::run: return "run";
    case Animation::showcase: return "showcase";
  }
  return "?";
}

int parse_options(int argc, char** argv, Options& options) {
  CLI::App app{"tressvk-demo: renders a head of simulated hair offscreen with the TressVK plugin and writes the "
               "frames as PNG files or a video.\nExit codes: 0 ok, 1 error (the message says which), 3 --video without ffmpeg."};
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
      {"none", Animation::none}, {"turn", Animation::turn}, {"shake", Animation::shake}, {"run", Animation::run},
      {"showcase", Animation::showcase}};
  app.add_option("--animate", options.animate,
                 "Motion: showcase (head turn, then a gust of wind from the front), none, turn, shake or run")
      ->transform(CLI::CheckedTransformer(animations, CLI::ignore_case))
      ->default_str("showcase");
  const std::map<std::string, Sample> samples{{"head", Sample::head}, {"sphere", Sample::sphere}};
  app.add_option("--sample", options.sample,
                 "Bundled sample without --asset: head (a face, groom grown on its scalp) or sphere (long128 groom)")
      ->transform(CLI::CheckedTransformer(samples, CLI::ignore_case))
      ->default_str("head");
  app.add_option("--groom", options.groom, "Bundled head: groom preset (straight or curly, as tressvk-bake groom)")
      ->check(CLI::IsMember({"straight", "curly"}))->capture_default_str();
  app.add_option("--export-head", options.export_head,
                 "Write the sample head (head.obj) and its scalp (scalp.obj, for tressvk-bake groom) into DIR, exit");
  app.add_option("--video", options.video,
                 "Encode the frames into this video file with ffmpeg (instead of a PNG per frame)");
  app.add_option("--params", options.params_file,
                 "JSON parameter file: simulation, settings, material, wind, lod (docs/getting-started.md)");
  app.add_option("--save-params", options.save_params, "Write the parameters in effect to this JSON file");
  app.add_option("--poster", options.poster, "Also write frame --poster-frame as this PNG");
  app.add_option("--poster-frame", options.poster_frame, "0-based frame index for --poster")->capture_default_str();
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
  app.add_option("--lod-target-px", options.lod_target_px,
                 "Hair LOD by coverage: thin sub-pixel strands until the drawn ones are about this many pixels wide "
                 "(0 = off; --lod-min-fraction is the floor)")
      ->check(CLI::Range(0.0f, 64.0f));
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
  if (!options.poster.empty() && options.poster_frame >= options.frames) {
    std::fprintf(stderr, "tressvk-demo: error: --poster-frame %u is not below --frames %u\n", options.poster_frame,
                 options.frames);
    return 1;
  }
  return -1;
}

}  // namespace tressvk::demo
