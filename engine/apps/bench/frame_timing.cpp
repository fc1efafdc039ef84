#include "frame_timing.hpp"

#include "tressvk_bench_spirv.h"

#include <tressvk/engine/buffer.hpp>
#include <tressvk/engine/descriptors.hpp>
#include <tressvk/engine/frame_loop.hpp>
#include <tressvk/engine/pipeline.hpp>
#include <tressvk/engine/sync.hpp>
#include <tressvk/host/glue.hpp>

#include <algorithm>
#include <barrier>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <thread>

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

// Calls tressvk_set_frame and tressvk_plan_frame for every instance, split over `threads` threads (the caller and
// threads - 1 workers that wait between frames), as a host's job system would.
class PlanThreads {
 public:
  PlanThreads(std::span<const TvkInstance> instances, uint32_t threads)
      : instances_(instances), threads_(std::max(1u, threads)), sync_(static_cast<std::ptrdiff_t>(threads_)) {
    for (uint32_t t = 1; t < threads_; ++t) workers_.emplace_back([this, t] {
      for (;;) {
        sync_.arrive_and_wait();  // a frame to plan, or the end
        if (stop_) return;
        work(t);
        sync_.arrive_and_wait();  // planned
      }
    });
  }
  ~PlanThreads() {
    stop_ = true;
    sync_.arrive_and_wait();
    for (std::thread& w : workers_) w.join();
  }
  PlanThreads(const PlanThreads&) = delete;
  PlanThreads& operator=(const PlanThreads&) = delete;

  // Every instance gets `frame`; throws engine::Error naming the first call that failed.
  void set_and_plan(TvkContext ctx, const TvkSimFrame& frame) {
    frame_ = &frame;
    failed_.assign(threads_, TVK_SUCCESS);
    sync_.arrive_and_wait();
    work(0);
    sync_.arrive_and_wait();
    for (uint32_t t = 0; t < threads_; ++t)
      if (failed_[t] != TVK_SUCCESS) host::check_tvk(failed_[t], ctx, failed_call_[t].c_str());
  }

 private:
  void work(uint32_t t) {
    const size_t n = instances_.size();
    for (size_t i = n * t / threads_; i < n * (t + 1) / threads_; ++i) {
      TvkResult r = tressvk_set_frame(instances_[i], frame_);
      if (r != TVK_SUCCESS) {
        failed_[t] = r;
        failed_call_[t] = "tressvk_set_frame";
        return;
      }
      if ((r = tressvk_plan_frame(instances_[i])) != TVK_SUCCESS) {
        failed_[t] = r;
        failed_call_[t] = "tressvk_plan_frame";
        return;
      }
    }
  }
  std::span<const TvkInstance> instances_;
  uint32_t threads_;
  std::barrier<> sync_;
  std::vector<std::thread> workers_;
  const TvkSimFrame* frame_ = nullptr;
  std::vector<TvkResult> failed_ = std::vector<TvkResult>(threads_, TVK_SUCCESS);
  std::vector<std::string> failed_call_ = std::vector<std::string>(threads_);
  bool stop_ = false;  // written before the barrier the workers wait on, read after it
};

// The clock probe (shaders/clock.comp): one workgroup's chain of kClockIterations dependent multiply-adds, recorded
// in every warm-up frame of a timed warm-up before the frame's own timestamps. About 76 us on an NVIDIA H100 at its
// working clock, 0.4 ms on lavapipe.
constexpr uint32_t kClockIterations = 20000;
struct ClockProbe {
  explicit ClockProbe(const engine::Device& dev)
      : sink(engine::create_buffer(dev, 256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::device_local)),
        set_layout(engine::create_set_layout(dev, {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}})),
        pool(dev, 1) {
    set = pool.allocate(set_layout.get());
    engine::write_buffer_descriptor(dev, set, 0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, sink.handle());
    engine::ComputePipelineDesc desc;
    desc.spirv = k_spv_clock_comp;
    desc.layout.set_layouts = {set_layout.get()};
    desc.layout.push_constant_size = 2 * sizeof(uint32_t);
    desc.debug_name = "tressvk-bench clock probe";
    pipeline = engine::create_compute_pipeline(dev, desc);
  }
  void record(VkCommandBuffer cmd) const {
    // After everything before it (the probe times the GPU alone), and its write-never sink after the last probe's.
    const engine::ResourceState before{VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT},
        after{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
    engine::cmd_memory_barrier(cmd, before, after);
    pipeline.cmd_bind(cmd);
    pipeline.cmd_bind_set(cmd, 0, set);
    const uint32_t push[2] = {kClockIterations, 0x3f800000u};  // (1.0f)
    pipeline.cmd_push(cmd, push);
    vkCmdDispatch(cmd, 1, 1, 1);  // (the simulation's entry barrier orders the frame after it)
  }
  engine::Buffer sink;
  engine::DeviceHandle<VkDescriptorSetLayout> set_layout;
  engine::DescriptorPool pool;
  VkDescriptorSet set = VK_NULL_HANDLE;
  engine::Pipeline pipeline;
};

// The fastest the probe has run in this process: a warm-up ends only once the probe is within its tolerance of it.
double g_fastest_clock_probe_ms = 0;

}  // namespace

FrameTimes time_frames(const engine::Device& dev, TvkContext ctx, std::span<const TvkInstance> instances,
                       model::FramePlanner& planner,
                       const std::function<TvkSimFrame(uint32_t)>& frame_of, const WarmUp& warmup, uint32_t frames,
                       uint32_t in_flight, uint32_t plan_threads) {
  FrameTimes out;
  std::unique_ptr<PlanThreads> plan_pool;
  if (plan_threads > 0) plan_pool = std::make_unique<PlanThreads>(instances, plan_threads);
  uint64_t steps_total = 0, frames_total = 0;
  uint32_t first_timed = UINT32_MAX;  // known once the warm-up ends
  std::vector<double> warm_ms;        // the warm-up frames' GPU times, as they complete
  std::vector<double> probe_ms;       // the warm-up frames' clock probes, as they complete
  // A warm-up that waits for the frame time to settle also waits for the GPU's clock (ClockProbe).
  const bool timed_warmup = warmup.max_ms > 0;
  std::unique_ptr<ClockProbe> probe;
  if (timed_warmup) probe = std::make_unique<ClockProbe>(dev);
  // (Reading a slot's results waits for every query in it: with a probe each frame writes all 4, else 2 are made.)
  engine::FrameLoop loop(dev, in_flight, probe ? 4u : 2u, [&](const engine::FrameLoop::Frame& fr) {
    const auto ms = fr.timestamps->elapsed_ms(0, 1);
    if (!ms) return;
    if (fr.number < first_timed) {
      warm_ms.push_back(*ms);
      if (const auto p = probe ? fr.timestamps->elapsed_ms(2, 3) : std::nullopt; p) probe_ms.push_back(*p);
    } else if (fr.number < first_timed + frames) {
      out.frame_ms.push_back(*ms);
    }
  });
  // The median clock probe of the newest (up to 8) warm-up frames, the process's fastest updated with it; 0: none.
  const auto probe_now = [&] {
    if (probe_ms.empty()) return 0.0;
    const double now = median_of({probe_ms.end() - std::min<std::ptrdiff_t>(8, std::ssize(probe_ms)), probe_ms.end()});
    if (g_fastest_clock_probe_ms <= 0 || now < g_fastest_clock_probe_ms) g_fastest_clock_probe_ms = now;
    return now;
  };
  // The GPU at its working clock: 8 probes in, within the tolerance of the fastest (no timestamps: the frame times
  // decide alone).
  const auto clock_up = [&] {
    if (!probe || !dev.timestamps_supported()) return true;
    if (probe_ms.size() < 8) return false;
    return probe_now() <= g_fastest_clock_probe_ms * (1.0 + warmup.tolerance);
  };
  const auto since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
  };
  const auto record = [&](uint32_t f) {
    const TvkSimFrame frame = frame_of(f);
    steps_total += planner.plan(frame).steps.size();
    ++frames_total;
    const auto h0 = std::chrono::steady_clock::now();
    if (plan_pool) {
      plan_pool->set_and_plan(ctx, frame);
    } else {
      for (TvkInstance inst : instances) host::check_tvk(tressvk_set_frame(inst, &frame), ctx, "tressvk_set_frame");
    }
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
    if (probe && first_timed == UINT32_MAX) {
      fr.timestamps->cmd_write(fr.cmd, 2, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
      probe->record(fr.cmd);
      fr.timestamps->cmd_write(fr.cmd, 3, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    }
    fr.timestamps->cmd_write(fr.cmd, 0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    const auto h1 = std::chrono::steady_clock::now();
    host::check_tvk(host::record_simulate(ctx, fr.cmd, instances), ctx, "tressvk_cmd_simulate");
    const double record_ms = since(h1);
    host += record_ms;
    if (first_timed != UINT32_MAX && f < first_timed + frames) {
      out.host_ms.push_back(host);
      out.record_ms.push_back(record_ms);
    }
    out.dispatches = std::max(out.dispatches, tressvk_get_recorded_dispatches(ctx));
    fr.timestamps->cmd_write(fr.cmd, 1, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    if (probe && first_timed != UINT32_MAX) {
      // Every query of the slot written, probe or not: reading the slot's results waits for all of them.
      fr.timestamps->cmd_write(fr.cmd, 2, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
      fr.timestamps->cmd_write(fr.cmd, 3, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    }
    loop.end();
  };
  const auto t_start = std::chrono::steady_clock::now();
  uint32_t f = 0;
  for (;; ++f) {
    if (f >= warmup.frames) {
      const double elapsed = since(t_start);
      if (elapsed >= warmup.max_ms) {
        out.warmup_settled = warmup.max_ms <= 0 || (settled(warm_ms, warmup.window_ms, warmup.tolerance) && clock_up());
        break;
      }
      // (tested every 32 frames: a window of small frames holds thousands)
      if (elapsed >= warmup.min_ms && f % 32u == 0u && settled(warm_ms, warmup.window_ms, warmup.tolerance) &&
          clock_up())
        break;
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
  // Reported once every warm-up frame has completed (a warm-up cut short by WarmUp::max_ms may end before any probe
  // result is back: the decision above used what was there).
  out.clock_probe_ms = probe_now();
  out.clock_probe_fastest_ms = probe_ms.empty() ? 0.0 : g_fastest_clock_probe_ms;
  out.steps_per_frame = frames_total ? double(steps_total) / double(frames_total) : 0;
  return out;
}

}  // namespace tressvk::bench
