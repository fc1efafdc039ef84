// tressvk-bench render: the hair renderer's speed at a resolution and, from the same run, its error against the
// brute-force sorted reference (tressvk/reference/strand_raster.hpp).
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

namespace tressvk::bench {

struct RenderBenchOptions {
  std::string asset;            // .tvkhair; empty: the bundled sample
  std::string mesh;             // OBJ head mesh (asset space)
  float mesh_scale = 1.0f;
  uint32_t width = 1920, height = 1080;
  std::string path = "compute";  // compute or raster
  std::string shade = "vertex";  // compute path: Kajiya-Kay per "vertex" (default) or per "fragment"
  uint32_t frames = 30;         // timed frames, back to back
  uint32_t warmup = 10;
  std::string sample = "head";  // no --asset: the bundled head sample, or the sphere sample (long128 groom)
  uint32_t guides = 1200, follows = 7, vertices = 48;  // the sphere sample's groom
  float lod_fraction = 1.0f;    // < 1: coverage-preserving LOD down to this fraction of the strands
  float lod_target_px = 0.0f;   // > 0: coverage-driven LOD (TvkLodSettings::target_width_px), no floor
  bool error_vs_full = false;
  double zoom = 1.0;            // camera distance over the framing distance (ViewControl::zoom)
  float shadow_extent = 1.6f;   // the shadow map's half-size over the scene radius (demo::Options::shadow_extent)   // also the error against the reference of ALL strands (the frame without LOD)
  std::string animate = "turn";
  std::string json, png, device;
  bool validation = false;
  bool no_reference = false;
  bool no_pass_timestamps = false;  // the plugin's per-pass timestamps off (the frame as a host runs it)
};

CLI::App* add_render_subcommand(CLI::App& app, RenderBenchOptions& options);
// Runs the benchmark; returns the process exit code (prints its own errors).
int run_render_bench(const RenderBenchOptions& options);

}  // namespace tressvk::bench
