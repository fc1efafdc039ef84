#include "frame_timing.hpp"

#include <tressvk/engine/frame_loop.hpp>
#include <tressvk/host/glue.hpp>

#include <algorithm>
#include <chrono>

namespace tressvk::bench {

FrameTimes time_frames(const engine::Device& dev, TvkContext ctx, TvkInstance inst, model::FramePlanner& planner,
                       const std::function<TvkSimFrame(uint32_t)>& frame_of, uint32_t warmup, uint32_t frames,
                       uint32_t in_flight) {
  FrameTimes out;
  uint64_t steps_total = 0, frames_total = 0;
  const uint32_t total = warmup + frames;
  engine::FrameLoop loop(dev, in_flight, 2, [&](const engine::FrameLoop::Frame& fr) {
    if (fr.number < warmup || fr.number >= total) return;
    if (auto ms = fr.timestamps->elapsed_ms(0, 1)) out.frame_ms.push_back(*ms);
  });
  const auto record = [&](uint32_t f) {
    const TvkSimFrame frame = frame_of(f);
    steps_total += planner.plan(frame).steps.size();
    ++frames_total;
    host::check_tvk(tressvk_set_frame(inst, &frame), ctx, "tressvk_set_frame");
    host::check_tvk(tressvk_new_frame(ctx), ctx, "tressvk_new_frame");
    const engine::FrameLoop::Frame& fr = loop.begin();
    // The frame that last used this slot is complete now: its per-pass timings name the dispatches of a frame.
    TvkPassTiming timings[32];
    const uint32_t n = tressvk_get_pass_timings(ctx, timings, 32);
    if (n) {
      uint32_t d = 0;
      double ms = 0;
      for (uint32_t i = 0; i < n && i < 32; ++i) {
        d += timings[i].dispatches;
        ms += timings[i].milliseconds;
      }
      out.dispatches = std::max(out.dispatches, d);
      if (f > warmup + in_flight && f <= total) out.sim_ms.push_back(ms);
    }
    fr.timestamps->cmd_write(fr.cmd, 0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    host::check_tvk(host::record_simulate(ctx, fr.cmd, inst), ctx, "tressvk_cmd_simulate");
    fr.timestamps->cmd_write(fr.cmd, 1, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    loop.end();
  };
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
  for (uint32_t f = 0; f < total; ++f) {
    if (f == warmup) t0 = std::chrono::steady_clock::now();
    record(f);
  }
  loop.finish();
  out.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  out.steps_per_frame = frames_total ? double(steps_total) / double(frames_total) : 0;
  return out;
}

}  // namespace tressvk::bench
