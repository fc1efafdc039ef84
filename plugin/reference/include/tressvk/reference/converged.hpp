// The converged reference (docs/accuracy.md): the same model on the double reference stepped far finer than any GPU
// setting (the planner's limits raised), and the tools to compare a configuration's trajectory with it: a prefix of
// the guides (an even thinning of the groom, so the reference stays cheap) and the matching of strands resampled at
// another vertex count by rest arc length.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

#include <tressvk/asset.hpp>

#include "tressvk/reference/scenes.hpp"
#include "tressvk/reference/simulator.hpp"

namespace tressvk::reference {

// The limits a converged reference runs under: step rates up to 7680 Hz and any number of steps per frame.
inline constexpr PlannerLimits kConvergedLimits{7680.0, 1024};

// Positions over a scene: per frame, the guides' positions in simulation space (whose origin follows the instance
// identically at every step rate, so trajectories at different rates compare vertex by vertex).
using Trajectory = std::vector<std::vector<Vec3>>;

struct TrajectoryOptions {
  double step_rate = 3840.0;       // Hz, up to kConvergedLimits.max_step_rate
  std::string_view scene = "settle";
  TvkSimModel model = TVK_SIM_MODEL_DEFAULT;  // TvkSimSettings::model of the reference
  uint32_t frames = 60;
  const SceneGeometry* geometry = nullptr;  // null: fitted to this asset's roots (scene_geometry)
  // Called on the simulator before the first frame (e.g. to pick a reference-only model option).
  std::function<void(Simulator&)> configure;
  // When set, receives per frame the simulation space's origin in the world (FramePlan::sim_origin).
  std::vector<Vec3>* sim_origins = nullptr;
};

// The guides' positions after each frame of the scene on the double reference, every group with `params` (one entry
// for all groups, or one per group), the planner's limits raised to kConvergedLimits. `median` (optional): the
// asset's median strand length.
Trajectory reference_trajectory(const asset::HairAsset& asset, std::span<const TvkSimParams> params,
                                const TrajectoryOptions& options, double* median = nullptr);

// The first `guides` guides of an asset (with their follows): an even thinning of the groom, since baked assets keep
// their guides in level-of-detail order (asset.hpp). Throws std::invalid_argument when guides is 0 or too many.
asset::HairAsset guide_prefix(const asset::HairAsset& asset, uint32_t guides);

// A trajectory of the same guides at another vertex count, matched by rest arc length: for each vertex of `target`
// (its rest arc fraction along its strand), the point at the same rest arc fraction of the same guide's polyline in
// `source`, linear between the source's vertices. Both rests must have the same guide count.
std::vector<Vec3> at_arc_fractions(std::span<const Vec3> source, const ModelRest& source_rest,
                                   const ModelRest& target_rest);

}  // namespace tressvk::reference
