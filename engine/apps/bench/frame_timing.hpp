// GPU time per frame the way `tressvk-bench perf` measures it (shared by perf and sweep): several frames in flight,
// no readback between timed frames, each frame timed by its own GPU timestamps around tressvk_cmd_simulate.
#pragma once

#include <tressvk/engine/device.hpp>
#include <tressvk/model/planner.hpp>
#include <tressvk/tressvk.h>

#include <cstdint>
#include <functional>
#include <vector>

namespace tressvk::bench {

struct FrameTimes {
  std::vector<double> frame_ms;  // per timed frame, the frame's own timestamps
  std::vector<double> sim_ms;    // per timed frame, the sum of the plugin's pass timings (when it was given timestamps)
  uint32_t dispatches = 0;       // most dispatches in a frame (from the plugin's pass timings)
  double steps_per_frame = 0;    // over every recorded frame
  double wall_ms = 0;            // CPU wall time of the timed frames, all of them
};

// Records warmup + frames frames, frame_of(0 .. warmup + frames - 1), into a frame loop of `in_flight` frames (the
// context must have been created with that many), waits for the last. `planner` is kept in step with the plugin's to
// count the steps. Throws engine::Error when a call fails.
FrameTimes time_frames(const engine::Device& device, TvkContext context, TvkInstance instance,
                       model::FramePlanner& planner, const std::function<TvkSimFrame(uint32_t)>& frame_of,
                       uint32_t warmup, uint32_t frames, uint32_t in_flight);

}  // namespace tressvk::bench
