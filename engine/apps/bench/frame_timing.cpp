#include "frame_timing.hpp"

#include <tressvk/engine/frame_loop.hpp>
#include <tressvk/host/glue.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>

namespace tressvk::bench {

namespace {

double median_of(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// The warm-up frames' GPU times have settled: the median of the newest `window_ms` of them within `tolerance` of the
// median of the window before.
bool settled(const std::vector<double>& ms, double window_ms, double tolerance) {
  std::vector<double> last, before;
  double sum = 0;
  size_t i = ms.size();
  for (; i > 0 && (sum < window_ms || last.size() < 10); --i) {
    last.push_back(ms[i - 1]);
    sum += ms[i - 1];
  }
  if (sum < window_ms) return false;
  sum = 0;
  for (; i > 0 && (sum < window_ms || before.size() < 10); --i) {
    before.push_back(ms[i - 1]);
    sum += ms[i - 1];
  }
  if (sum < window_ms) return false;
  const double a = median_of(std::move(last)), b = median_of(std::move(before));
  return std::abs(a - b) <= tolerance * a;
}

}  // namespace

FrameTimes time_frames(const engine::Device& dev, TvkContext ctx, std::span<const TvkInstance> instances,
                       model::FramePlanner& planner,
                       const std::function<TvkSimFrame(uint32_t)>& frame_of, const WarmUp& warmup, uint32_t frames,
                       uint32_t in_flight) {
  FrameTimes out;
  uint64_t steps_total = 0, frames_total = 0;
  uint32_t first_timed = UINT32_MAX;  // known once the warm-up ends
  std::vector<double> warm_ms;        // the warm-up frames' GPU times, as they complete
  engine::FrameLoop loop(dev, in_flight, 2, [&](const engine::FrameLoop::Frame& fr) {
    const auto ms = fr.timestamps->elapsed_ms(0, 1);
    if (!ms) return;
    if (fr.number < first_timed) warm_ms.push_back(*ms);
    else if (fr.number < first_timed + frames) out.frame_ms.push_back(*ms);
  });
  const auto since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
  };
  const auto record = [&](uint32_t f) {
    const TvkSimFrame frame = frame_of(f);
    steps_total += planner.plan(frame).steps.size();
    ++frames_total;
    const auto h0 = std::chrono::steady_clock::now();
    for (TvkInstance inst : instances) host::check_tvk(tressvk_set_frame(inst, &frame), ctx, "tressvk_set_frame");
    host::check_tvk(tressvk_new_frame(ctx), ctx, "tressvk_new_frame");
    double host = since(h0);
    const engine::FrameLoop::Frame& fr = loop.begin();
    // The frame that last used this slot is complete now: its per-pass timings name the dispatches of a frame.
    TvkPassTiming timings[32];
    const uint32_t n = tressvk_get_pass_timings(ctx, timings, 32);
    if (n) {
      double ms = 0;
      for (uint32_t i = 0; i < n && i < 32; ++i) ms += timings[i].milliseconds;
      if (first_timed != UINT32_MAX && f > first_timed + in_flight && f <= first_timed + frames)
        out.sim_ms.push_back(ms);
    }
    fr.timestamps->cmd_write(fr.cmd, 0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    const auto h1 = std::chrono::steady_clock::now();
    host::check_tvk(host::record_simulate(ctx, fr.cmd, instances), ctx, "tressvk_cmd_simulate");
    host += since(h1);
    if (first_timed != UINT32_MAX && f < first_timed + frames) out.host_ms.push_back(host);
    out.dispatches = std::max(out.dispatches, tressvk_get_recorded_dispatches(ctx));
    fr.timestamps->cmd_write(fr.cmd, 1, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    loop.end();
  };
  const auto t_start = std::chrono::steady_clock::now();
  uint32_t f = 0;
  for (;; ++f) {
    if (f >= warmup.frames) {
      const double elapsed = since(t_start);
      if (elapsed >= warmup.max_ms) {
        out.warmup_settled = warmup.max_ms <= 0 || settled(warm_ms, warmup.window_ms, warmup.tolerance);
        break;
      }
      // (tested every 32 frames: a window of small frames holds thousands)
      if (elapsed >= warmup.min_ms && f % 32u == 0u && settled(warm_ms, warmup.window_ms, warmup.tolerance)) break;
    }
    record(f);
  }
  first_timed = f;
  out.warmup_frames = f;
  out.warmup_ms = since(t_start);
  const auto t0 = std::chrono::steady_clock::now();
  for (; f < first_timed + frames; ++f) record(f);
  loop.finish();
  out.wall_ms = since(t0);
  out.steps_per_frame = frames_total ? double(steps_total) / double(frames_total) : 0;
  return out;
}

}  // namespace tressvk::bench
