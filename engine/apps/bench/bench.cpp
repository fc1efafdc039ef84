#include "bench.hpp"
#include "common.hpp"

#include <tressvk/engine/buffer.hpp>
#include <tressvk/engine/check.hpp>
#include <tressvk/host/hair_readback.hpp>
#include <tressvk/host/plugin_host.hpp>
#include <tressvk/asset_io.hpp>
#include <tressvk/reference/metrics.hpp>
#include <tressvk/reference/penetration.hpp>
#include <tressvk/reference/scenes.hpp>
#include <tressvk/reference/simulator.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

namespace tressvk::bench {

namespace {

// The groom, scene and sizes the result describes.
void describe(CompareResult& out, const engine::Device& dev, const asset::HairAsset& groom,
              const std::string& groom_name, const CompareOptions& opt) {
  out.device = dev.description();
  out.groom = groom_name;
  out.scene = opt.scene;
  out.frames = opt.frames;
  out.guides = groom.guide_count();
  out.follows = groom.follow_per_guide;
  out.vertices_per_strand = groom.vertices_per_strand;
  out.guide_vertices = uint64_t{out.guides} * out.vertices_per_strand;
  out.rendered_vertices = out.guide_vertices * (1 + out.follows);
}

// What the frames add up: GPU pass timings, reference CPU time, and the errors of the measured frames.
struct Tally {
  std::vector<double> gpu_ms, cpu_ms, step_errors;
  std::map<std::string, std::vector<double>> pass_ms;
  std::map<std::string, uint32_t> pass_dispatches;
  double traj_sum_sq = 0, stretch_mean_sum = 0;
  uint64_t traj_count = 0, steps_total = 0;

  // The completed frame's pass timings: each pass's time, their sum, and (when asked) each pass's dispatches.
  void collect_timings(TvkContext ctx, bool dispatches) {
    TvkPassTiming timings[16];
    const uint32_t n = tressvk_get_pass_timings(ctx, timings, 16);
    double sum = 0;
    for (uint32_t i = 0; i < n && i < 16; ++i) {
      sum += timings[i].milliseconds;
      pass_ms[timings[i].name].push_back(timings[i].milliseconds);
      if (dispatches) pass_dispatches[timings[i].name] = timings[i].dispatches;
    }
    if (n) gpu_ms.push_back(sum);
  }

  // A measured frame's GPU state against the step reference (reloaded from the previous GPU state, when
  // `step_error_now`) and the free-running one (with opt.trajectory), and its stretch and health.
  // before: the GPU state the step reference was loaded with (step_error_now), whose sleeping guides it holds.
  void measure(CompareResult& out, const host::HairState& before, const host::HairState& state,
               const reference::Simulator& step_ref, const reference::Simulator& traj_ref, bool step_error_now,
               const CompareOptions& opt, double median_length) {
    if (step_error_now) {
      const std::vector<std::array<double, 3>> expected = host::held_where_skipped(before, state, step_ref.positions());
      const auto e = reference::position_error(std::span<const std::array<double, 3>>(state.positions),
                                               std::span<const std::array<double, 3>>(expected), median_length);
      step_errors.push_back(e.max_rel);
      out.step_error_max_rel = std::max(out.step_error_max_rel, e.max_rel);
    }
    if (opt.trajectory) {
      const auto te =
          reference::position_error(std::span<const std::array<double, 3>>(state.positions), traj_ref.positions(), median_length);
      traj_sum_sq += te.rms_rel * te.rms_rel;
      out.trajectory_error_max_rel = std::max(out.trajectory_error_max_rel, te.max_rel);
    }
    ++traj_count;
    const auto st = reference::stretch(std::span<const std::array<double, 3>>(state.positions), step_ref.rest());
    stretch_mean_sum += st.mean;
    out.stretch_max = std::max(out.stretch_max, st.max);
    const auto h = reference::health(std::span<const std::array<double, 3>>(state.positions), step_ref.rest());
    out.nan_strands = std::max(out.nan_strands, h.nan_strands);
    out.exploded_strands = std::max(out.exploded_strands, h.exploded_strands);
  }

  // The result's passes, medians and means, once every frame is in.
  void summarise(CompareResult& out, TvkContext ctx, TvkInstance inst, uint32_t total, const CompareOptions& opt) {
    const uint32_t np = tressvk_get_recorded_passes(ctx, nullptr, 0);
    std::vector<const char*> names(np);
    tressvk_get_recorded_passes(ctx, names.data(), np);
    out.passes.assign(names.begin(), names.end());
    // An instance whose every guide sleeps records nothing (docs/simulation.md, "Idle instances"): then the passes
    // are those the frames before it timed.
    if (out.passes.empty())
      for (const auto& [name, times] : pass_ms) out.passes.push_back(name);
    for (const std::string& p : out.passes) {
      out.pass_times.push_back({p, median(pass_ms[p]), pass_dispatches[p]});
      out.dispatches_per_frame += pass_dispatches[p];
    }
    TvkInstanceStats stats{};
    tressvk_get_instance_stats(inst, &stats);
    out.nonfinite_resets = stats.nonfinite_strand_resets;
    out.gpu_ms_per_frame = median(gpu_ms);
    out.gpu_ms_p99 = percentile(gpu_ms, 0.99);
    out.cpu_reference_ms_per_frame = median(cpu_ms);
    out.steps_per_frame = static_cast<double>(steps_total) / total;
    double sum_sq = 0;
    for (double e : step_errors) sum_sq += e * e;
    out.step_error_rms_rel = step_errors.empty() ? 0 : std::sqrt(sum_sq / static_cast<double>(step_errors.size()));
    out.stretch_mean = traj_count ? stretch_mean_sum / static_cast<double>(traj_count) : 0;
    out.trajectory_error_rms_rel = traj_count && opt.trajectory ? std::sqrt(traj_sum_sq / static_cast<double>(traj_count)) : 0;
  }
};

}  // namespace

CompareResult run_compare(const engine::Device& dev, const asset::HairAsset& groom, const std::string& groom_name,
                          const CompareOptions& opt) {
  CompareResult out;
  describe(out, dev, groom, groom_name, opt);

  // One frame in flight: every frame is waited for (the state is read back).
  TvkContext ctx = host::create_context(dev, 1, /*timestamps=*/true);
  const std::vector<std::byte> bytes = asset::write(groom);
  TvkAsset asset = host::load_asset(dev, ctx, bytes);
  const std::vector<TvkSimParams> params(std::max<size_t>(1, groom.groups.size()), opt.params);
  TvkInstance inst = host::create_instance(ctx, asset, opt.settings, opt.params);

  reference::Simulator step_ref(groom, params, opt.settings);  // reloaded from the GPU state before each frame
  reference::Simulator traj_ref(groom, params, opt.settings);  // free-running from the same initial state
  const reference::SceneGeometry geometry = reference::scene_geometry(step_ref.rest());
  const double median_length = step_ref.median_strand_length();
  out.median_strand_length_m = median_length;

  Tally tally;
  host::HairState state;  // GPU state after the previous frame, when it was read back
  reference::PenetrationTracker penetration;
  uint32_t penetration_frame = ~0u;  // the frame last given to it
  bool state_is_previous = false;
  const uint32_t total = opt.warmup + opt.frames;
  const uint32_t every = std::max(1u, opt.step_error_every);
  const auto measured = [&](uint32_t f) { return f >= opt.warmup && f < total && (f - opt.warmup) % every == 0; };
  for (uint32_t f = 0; f < total; ++f) {
    const bool timed = f >= opt.warmup;
    const TvkSimFrame frame = reference::scene_frame(opt.scene, f, geometry);
    const bool step_error_now = measured(f) && state_is_previous;
    if (step_error_now) step_ref.set_state(state.positions, state.previous, state.previous_previous);
    const auto t0 = std::chrono::steady_clock::now();
    const reference::FramePlan plan = opt.trajectory ? traj_ref.advance(frame) : traj_ref.planner().plan(frame);
    const auto t1 = std::chrono::steady_clock::now();
    if (step_error_now)
      step_ref.advance(frame);
    else
      step_ref.planner().plan(frame);  // keep its planner in step with the GPU's

    host::check_tvk(tressvk_set_frame(inst, &frame), ctx, "tressvk_set_frame");
    host::check_tvk(tressvk_new_frame(ctx), ctx, "tressvk_new_frame");
    if (timed && f > opt.warmup) {
      tally.collect_timings(ctx, true);  // the previous frame is complete (frames_in_flight = 1)
    }
    dev.run_commands([&](VkCommandBuffer cmd) {
      host::check_tvk(host::record_simulate(ctx, cmd, inst), ctx, "tressvk_cmd_simulate");
    });
    tally.steps_total += plan.steps.size();
    if (timed && opt.trajectory) tally.cpu_ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());

    state_is_previous = false;
    if (!measured(f) && !measured(f + 1)) continue;
    host::HairState before = std::move(state);
    state = host::read_hair_state(dev, inst);
    state_is_previous = true;
    if (measured(f)) {
      tally.measure(out, before, state, step_ref, traj_ref, step_error_now, opt, median_length);
      penetration.add(std::span<const std::array<double, 3>>(state.positions), plan, frame.dt, step_ref.rest(),
                      penetration_frame + 1 == f);
      penetration_frame = f;
    }
  }
  // Timings of the last frame.
  tressvk_new_frame(ctx);
  tally.collect_timings(ctx, false);  // the dispatch counts stay those of the timed frames
  tally.summarise(out, ctx, inst, total, opt);
  out.penetration_depth_rel = penetration.stats().depth_rel;
  out.post_contact_speed_mps = penetration.stats().post_contact_speed;

  dev.wait_idle();
  tressvk_destroy_instance(inst);
  tressvk_destroy_asset(asset);
  tressvk_destroy_context(ctx);
  return out;
}

}  // namespace tressvk::bench
