// The step error of the current scene against the double-precision reference, as tressvk-bench compare measures
// it: the GPU state after frame k-1 is loaded into the reference, both advance frame k with the same input, and the
// largest vertex distance is reported relative to the median strand length. A FramePlanner follows every frame so
// the reference plans frame k exactly as the plugin does (substeps, interpolated head motion).
#pragma once

#include "params.hpp"

#include <tressvk/host/hair_readback.hpp>
#include <tressvk/reference/simulator.hpp>

#include <cstddef>
#include <memory>
#include <span>

namespace tressvk::demo {

class StepErrorProbe {
 public:
  StepErrorProbe(std::span<const std::byte> asset_bytes, const Params& params);
  ~StepErrorProbe();

  // Every frame that is not measured: keeps the planner in step with the plugin's.
  void track(const TvkSimFrame& frame);
  // Frame k is measured: before = the GPU state after frame k-1; params = those in effect now.
  void start(const TvkSimFrame& frame, const host::HairState& before, const Params& params);
  // after = the GPU state after frame k. Returns the largest vertex distance / median strand length over the strands
  // the frame wrote: draw_strands, the count it gave tressvk_set_draw_strands (0: every strand).
  double finish(const host::HairState& after, uint32_t draw_strands = 0);

 private:
  asset::HairAsset asset_;
  std::unique_ptr<reference::Simulator> tracker_;   // only its planner is used, every frame
  std::unique_ptr<reference::Simulator> measured_;  // the frame being measured
  host::HairState before_;                          // the state it was loaded with (its sleeping guides held)
};

}  // namespace tressvk::demo
