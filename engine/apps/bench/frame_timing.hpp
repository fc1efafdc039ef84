// GPU time per frame the way `tressvk-bench perf` measures it (shared by perf and sweep): several frames in flight,
// no readback between timed frames, each frame timed by its own GPU timestamps around tressvk_cmd_simulate.
#pragma once

#include <tressvk/engine/device.hpp>
#include <tressvk/model/planner.hpp>
#include <tressvk/tressvk.h>

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace tressvk::bench {

// How long time_frames runs frames before it times them: at least `frames` frames and `min_ms` of wall time, then
// until the GPU time per frame has settled: the median frame of the last `window_ms` of GPU work within `tolerance`
// of the window's before it (a GPU's clock can take a second to climb back after the GPU idled for a moment, and a
// timed window on the climb reads slow) and a clock probe within `tolerance` of its fastest in this process
// (FrameTimes::clock_probe_ms), or `max_ms`, whichever comes first. min_ms = max_ms = 0: frames only.
struct WarmUp {
  uint32_t frames = 0;
  double min_ms = 0, max_ms = 0;
  double window_ms = 100, tolerance = 0.02;
};

struct FrameTimes {
  std::vector<double> frame_ms;  // per timed frame, the frame's own timestamps
  std::vector<double> sim_ms;    // per timed frame, the sum of the plugin's pass timings (when it was given timestamps)
  std::vector<double> host_ms;   // per timed frame, wall time of the plugin's per-frame calls: tressvk_set_frame (and
                                 // with plan threads tressvk_plan_frame) for every instance, tressvk_new_frame and
                                 // tressvk_cmd_simulate (the frame loop's own waits for a free slot left out)
  std::vector<double> record_ms; // per timed frame, the tressvk_cmd_simulate call alone (what stays on the recording
                                 // thread once plan threads have planned every instance)
  uint32_t dispatches = 0;       // most dispatches in a frame (tressvk_get_recorded_dispatches)
  double steps_per_frame = 0;    // over every recorded frame
  double wall_ms = 0;            // CPU wall time of the timed frames, all of them
  uint32_t warmup_frames = 0;    // frames run before the timed ones
  double warmup_ms = 0;          // their wall time
  bool warmup_settled = true;    // false: WarmUp::max_ms ran out before the frame time settled
  // A timed warm-up (WarmUp::max_ms > 0) also times a clock probe (shaders/clock.comp) in each warm-up frame and ends
  // only once the probe runs within WarmUp::tolerance of the fastest it has run in this process: the GPU at its working
  // clock. The probe's median over the last warm-up frames, and that fastest (0: no probe).
  double clock_probe_ms = 0;
  double clock_probe_fastest_ms = 0;
};

// Records the warm-up frames and then `frames` timed ones, frame_of(0, 1, ...), into one frame loop of `in_flight`
// frames (the context must have been created with that many; the GPU is never left idle between warm-up and timed
// frames), waits for the last. Every instance gets the same frame, all of them in one tressvk_cmd_simulate. `planner`
// is kept in step with the plugin's to count the steps. plan_threads > 0: the instances' tressvk_set_frame and
// tressvk_plan_frame run on that many threads (the calling one among them), as a job system's workers would call them;
// 0: tressvk_cmd_simulate plans every instance. Throws engine::Error when a call fails.
FrameTimes time_frames(const engine::Device& device, TvkContext context, std::span<const TvkInstance> instances,
                       model::FramePlanner& planner, const std::function<TvkSimFrame(uint32_t)>& frame_of,
                       const WarmUp& warmup, uint32_t frames, uint32_t in_flight, uint32_t plan_threads = 0);

}  // namespace tressvk::bench
