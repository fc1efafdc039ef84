// One instance simulated on the GPU frame by frame through the plugin's C interface with its state read back after
// every frame (shared by `sweep` and `hardcases`): the trajectory of its first guides, the one-frame step error
// against the double reference loaded with the GPU state before each frame, stretch, health, non-finite resets,
// frames refused by tressvk_set_frame and the penetration metric.
#pragma once

#include <tressvk/asset.hpp>
#include <tressvk/engine/device.hpp>
#include <tressvk/reference/converged.hpp>
#include <tressvk/reference/penetration.hpp>
#include <tressvk/tressvk.h>

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace tressvk::bench {

struct TrackOptions {
  uint32_t frames = 60;
  std::function<TvkSimFrame(uint32_t)> frame_of;  // the host's frame f (may hold values set_frame must refuse)
  uint32_t keep_guides = 0;                       // guides whose positions are kept every frame
  bool step_error = true;                         // load the reference with the GPU state and compare each frame
};

struct TrackResult {
  reference::Trajectory trajectory;  // the first keep_guides guides after each frame, simulation space
  std::vector<reference::Vec3> origins;  // per frame, the simulation space's origin in the world (m)
  double median_strand_length = 0;   // m
  double step_error_max_rel = 0;     // one frame, / median strand length
  double stretch_max = 0, stretch_mean = 0;
  uint32_t nan_strands = 0, exploded_strands = 0;  // worst frame
  uint32_t nonfinite_resets = 0;
  uint32_t refused_frames = 0;       // frames tressvk_set_frame refused (the instance then advances no time)
  std::string first_refusal;         // its message
  reference::PenetrationStats penetration;
  double steps_per_frame = 0;
};

// Throws engine::Error when a plugin call other than a refused set_frame fails.
TrackResult track(const engine::Device& device, TvkContext context, const asset::HairAsset& groom,
                  std::span<const TvkSimParams> params, const TvkSimSettings& settings, const TrackOptions& options);

}  // namespace tressvk::bench
