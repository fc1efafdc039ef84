#include "step_error.hpp"

#include <tressvk/asset_io.hpp>
#include <tressvk/engine/check.hpp>
#include <tressvk/reference/metrics.hpp>

#include <algorithm>
#include <vector>

namespace tressvk::demo {

namespace {

std::vector<TvkSimParams> group_params(const asset::HairAsset& a, const Params& params) {
  return std::vector<TvkSimParams>(std::max<size_t>(1, a.groups.size()), params.simulation);
}

}  // namespace

StepErrorProbe::StepErrorProbe(std::span<const std::byte> asset_bytes, const Params& params) {
  asset::ReadResult r = asset::read(asset_bytes);
  if (!r.ok()) throw engine::Error("step error: the scene's asset does not read back: " + r.error);
  asset_ = std::move(r.asset);
  const std::vector<TvkSimParams> p = group_params(asset_, params);
  tracker_ = std::make_unique<reference::Simulator>(asset_, p, params.settings);
}

StepErrorProbe::~StepErrorProbe() = default;

void StepErrorProbe::track(const TvkSimFrame& frame) { tracker_->planner().plan(frame); }

void StepErrorProbe::start(const TvkSimFrame& frame, const host::HairState& before, const Params& params) {
  const std::vector<TvkSimParams> p = group_params(asset_, params);
  measured_ = std::make_unique<reference::Simulator>(asset_, p, params.settings);
  measured_->planner() = tracker_->planner();  // the plugin's planning history up to frame k-1
  measured_->set_state(std::span<const reference::Simulator::Point>(before.positions),
                       std::span<const reference::Simulator::Point>(before.previous),
                       std::span<const reference::Simulator::Point>(before.previous_previous));
  measured_->advance(frame);
  tracker_->planner().plan(frame);
  before_ = before;
}

double StepErrorProbe::finish(const host::HairState& after, uint32_t draw_strands) {
  if (!measured_) throw engine::Error("step error: no frame is being measured");
  // Follow strands above the draw count are not written (tressvk_set_draw_strands): only the written ones compare.
  const size_t written = size_t{asset_.simulated_strands(draw_strands)} * asset_.vertices_per_strand;
  const auto e = reference::position_error(std::span<const std::array<double, 3>>(after.positions).first(written),
                                           std::span<const std::array<double, 3>>(
                                               host::held_where_skipped(before_, after, measured_->positions()))
                                               .first(written),
                                           measured_->median_strand_length());
  measured_.reset();
  return e.max_rel;
}

}  // namespace tressvk::demo
