#include "gpu_track.hpp"

#include <tressvk/asset_io.hpp>
#include <tressvk/host/glue.hpp>
#include <tressvk/host/hair_readback.hpp>
#include <tressvk/reference/metrics.hpp>
#include <tressvk/reference/simulator.hpp>

#include <algorithm>

namespace tressvk::bench {

TrackResult track(const engine::Device& dev, TvkContext ctx, const asset::HairAsset& groom,
                  std::span<const TvkSimParams> params, const TvkSimSettings& settings, const TrackOptions& opt) {
  TrackResult out;
  const std::vector<std::byte> bytes = asset::write(groom);
  TvkAsset asset = host::load_asset(dev, ctx, bytes);
  TvkInstance inst = nullptr;
  try {
    inst = host::create_instance(ctx, asset, settings, params[0]);
    for (uint32_t g = 0; g < params.size(); ++g)
      host::check_tvk(tressvk_set_sim_params(inst, g, &params[g]), ctx, "tressvk_set_sim_params");
    reference::Simulator ref(groom, params, settings);
    const reference::ModelRest& rest = ref.rest();
    out.median_strand_length = ref.median_strand_length();
    const size_t n = groom.vertices_per_strand;
    const size_t keep = size_t{std::min<uint32_t>(opt.keep_guides, groom.guide_count())} * n;
    reference::PenetrationTracker penetration;
    host::HairState state;
    TvkSimFrame last_good{};
    bool have_good = false, have_state = false;
    uint64_t steps = 0;
    double stretch_sum = 0;
    for (uint32_t f = 0; f < opt.frames; ++f) {
      TvkSimFrame frame = opt.frame_of(f);
      const TvkResult set = tressvk_set_frame(inst, &frame);
      if (set != TVK_SUCCESS) {
        // Refused: the instance keeps its pose and advances no time; the reference is given the same.
        if (out.refused_frames++ == 0) out.first_refusal = tressvk_last_error(ctx);
        if (!have_good) continue;
        frame = last_good;
        frame.dt = 0;
        frame.teleport = frame.reset = 0;
      } else {
        last_good = frame;
        have_good = true;
      }
      if (opt.step_error && have_state) ref.set_state(state.positions, state.previous, state.previous_previous);
      const reference::FramePlan plan = ref.advance(frame);
      steps += plan.steps.size();
      host::check_tvk(tressvk_new_frame(ctx), ctx, "tressvk_new_frame");
      dev.run_commands([&](VkCommandBuffer c) {
        host::check_tvk(host::record_simulate(ctx, c, inst), ctx, "tressvk_cmd_simulate");
      });
      host::HairState before = std::move(state);
      state = host::read_hair_state(dev, inst);
      const std::span<const std::array<double, 3>> pos(state.positions);
      if (opt.step_error) {
        // Guides the GPU skipped (asleep) held in the reference too; before the first read `before` is empty and
        // holds nothing.
        const std::vector<std::array<double, 3>> expected = host::held_where_skipped(before, state, ref.positions());
        const auto e = reference::position_error(pos, std::span<const std::array<double, 3>>(expected),
                                                 out.median_strand_length);
        out.step_error_max_rel = std::max(out.step_error_max_rel, e.max_rel);
      }
      have_state = true;
      const auto st = reference::stretch(pos, rest);
      stretch_sum += st.mean;
      out.stretch_max = std::max(out.stretch_max, st.max);
      const auto h = reference::health(pos, rest);
      out.nan_strands = std::max(out.nan_strands, h.nan_strands);
      out.exploded_strands = std::max(out.exploded_strands, h.exploded_strands);
      penetration.add(pos, plan, frame.dt, rest);
      if (keep) {
        std::vector<reference::Vec3>& kept = out.trajectory.emplace_back(keep);
        for (size_t i = 0; i < keep; ++i) kept[i] = {pos[i][0], pos[i][1], pos[i][2]};
        TvkInstanceBuffers b{};
        host::check_tvk(tressvk_get_instance_buffers(inst, &b), ctx, "tressvk_get_instance_buffers");
        out.origins.push_back({b.origin[0], b.origin[1], b.origin[2]});
      }
    }
    out.stretch_mean = opt.frames ? stretch_sum / opt.frames : 0;
    out.steps_per_frame = opt.frames ? double(steps) / opt.frames : 0;
    out.penetration = penetration.stats();
    TvkInstanceStats stats{};
    host::check_tvk(tressvk_get_instance_stats(inst, &stats), ctx, "tressvk_get_instance_stats");
    out.nonfinite_resets = stats.nonfinite_strand_resets;
  } catch (...) {
    dev.wait_idle();
    if (inst) tressvk_destroy_instance(inst);
    tressvk_destroy_asset(asset);
    throw;
  }
  dev.wait_idle();
  tressvk_destroy_instance(inst);
  tressvk_destroy_asset(asset);
  return out;
}

}  // namespace tressvk::bench
