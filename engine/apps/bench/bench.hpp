// One benchmark run: a groom in a scene, simulated on the GPU through the plugin's C interface (the way a host
// engine drives it) and by the double-precision reference in the same process, frame by frame.
#pragma once

#include <tressvk/asset.hpp>
#include <tressvk/engine/device.hpp>
#include <tressvk/tressvk.h>

#include <cstdint>
#include <string>
#include <vector>

namespace tressvk::bench {

struct CompareOptions {
  std::string scene = "shake";
  uint32_t frames = 300;
  uint32_t warmup = 30;              // frames run before timing (pipelines compiled, caches warm)
  uint32_t step_error_every = 1;     // measure the one-frame step error every Nth frame (it reads the state back)
  bool trajectory = true;            // also run a free-running reference every frame (costly for big grooms)
  TvkSimParams params = TVK_SIM_PARAMS_DEFAULT_INIT;
  TvkSimSettings settings = TVK_SIM_SETTINGS_DEFAULT_INIT;
};

struct PassTime {
  std::string name;
  double median_ms = 0;
  uint32_t dispatches = 0;           // per frame
};

struct CompareResult {
  std::string device;
  std::string groom;
  std::string scene;
  uint32_t frames = 0;
  uint32_t guides = 0, follows = 0, vertices_per_strand = 0;
  uint64_t guide_vertices = 0, rendered_vertices = 0;
  double median_strand_length_m = 0;
  double steps_per_frame = 0;
  double gpu_ms_per_frame = 0;        // median over timed frames of the summed pass timestamps
  double gpu_ms_p99 = 0;
  double cpu_reference_ms_per_frame = 0;  // median, double precision, one thread, same frames
  uint32_t dispatches_per_frame = 0;
  double step_error_max_rel = 0;
  double step_error_rms_rel = 0;
  double trajectory_error_rms_rel = 0;
  double trajectory_error_max_rel = 0;
  double stretch_mean = 0, stretch_max = 0;
  uint32_t nan_strands = 0, exploded_strands = 0, nonfinite_resets = 0;
  // Penetration (reference/penetration.hpp), over the measured frames: deepest free vertex inside a capsule / its
  // radius, fastest vertex relative to the surface in the frame after a contact (m/s).
  double penetration_depth_rel = 0, post_contact_speed_mps = 0;
  std::vector<std::string> passes;
  std::vector<PassTime> pass_times;
};

CompareResult run_compare(const engine::Device& device, const asset::HairAsset& groom, const std::string& groom_name,
                          const CompareOptions& options);

}  // namespace tressvk::bench
