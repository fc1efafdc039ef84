// tressvk-demo's command line.
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace tressvk::demo {

// showcase: a head turn and then a gust of wind from the front (the default: what the sample is made to show).
enum class Animation { none, turn, shake, run, showcase };
// How the hair is drawn: the compute strand rasterizer (tressvk_cmd_raster_hair + tressvk_cmd_composite_hair) or
// the raster path of quads in the host's pass (tressvk_cmd_draw_hair).
enum class HairPath { compute, raster };

// The bundled sample when no --asset is given: the procedural head with a face and a groom grown on its scalp,
// or the older sphere head with the long128 groom (kept for the renderer's golden images).
enum class Sample { head, sphere };

struct Options {
  uint32_t frames = 1;
  std::string out_dir = "out/demo";
  uint32_t width = 960;
  uint32_t height = 540;
  std::string device;  // index or name substring; empty: TRESSVK_DEVICE or automatic
  bool validation = false;
  bool list_devices = false;

  std::string asset;   // .tvkhair file; empty: the bundled procedural groom on the procedural head
  std::string mesh;    // OBJ head/character mesh (in the asset's space); empty: procedural head if bundled
  float mesh_scale = 1.0f;  // OBJ units to metres (bake the hair with the same --scale)
  Sample sample = Sample::head;
  std::string groom = "straight";  // bundled head: groom generator preset (tressvk-bake groom --preset)
  std::string export_head;         // directory: write the sample head.obj and scalp.obj there and exit
  std::string video;               // .mp4 (or any container ffmpeg knows): frames piped to ffmpeg, no PNGs
  std::string poster;              // PNG: one frame (--poster-frame) written here as well
  uint32_t poster_frame = 0;       // 0-based frame index for --poster
  bool draw_hair = true;           // false: the same frame without the hair (tests: what the hair covers)
  std::string params_file;         // JSON parameter file (params.hpp): simulation, material, wind, LOD
  std::string save_params;         // write the parameters in effect to this JSON file
  Animation animate = Animation::showcase;
  float wind = 0.0f;   // m/s^2
  bool shadows = true;
  bool pass_timestamps = false;  // the plugin times each of its passes and DemoApp::pass_ms() collects every frame's
                                 // (tressvk-bench render)
  HairPath hair_path = HairPath::compute;  // --path
  uint32_t raster_flags = 0;               // tests: TVK_RASTER_* flags of the compute path (capture, reverse)
  // Not on the command line of the default run, but used by tests and docs:
  float camera_distance = 0.0f;   // m from the framed centre; 0 = frame the scene
  float shadow_extent = 1.6f;     // the shadow map's half-size over the scene's radius (larger: the hair covers less)
  float lod_start = 0.0f;         // m; LOD from start to end distance down to lod_min_fraction (0 = off)
  float lod_end = 0.0f;
  float lod_min_fraction = 0.25f;
  float lod_target_px = 0.0f;     // > 0: coverage-driven LOD (TvkLodSettings::target_width_px; replaces the distances)
  uint32_t guides = 1200;         // bundled groom: guides and follow hairs per guide
  uint32_t follows = 7;
  std::array<double, 3> world_offset{};  // m: where the scene sits in the world (precision far from the origin)
  bool pass_timings = false;       // the plugin records per-pass GPU times; DemoApp::pass_timings() reads the newest
  bool step_error = false;         // keep a reference planner in step so DemoApp::request_step_error works
  double frame_time = 1.0 / 60.0;  // s per frame (0 = the hair stays in its rest pose: renderer-only tests)
};

// Parses argv. Returns an exit code to stop with (0 after --help), or -1 to go on.
int parse_options(int argc, char** argv, Options& options);

const char* animation_name(Animation a);

}  // namespace tressvk::demo
