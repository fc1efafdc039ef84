#include "tressvk/reference/converged.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace tressvk::reference {

Trajectory reference_trajectory(const asset::HairAsset& asset, std::span<const TvkSimParams> params,
                                const TrajectoryOptions& options, double* median) {
  TvkSimSettings s = TVK_SIM_SETTINGS_DEFAULT_INIT;
  s.time.step_rate = static_cast<float>(options.step_rate);
  s.time.max_steps_per_frame = kConvergedLimits.max_steps_per_frame;
  s.model = options.model;
  Simulator sim(asset, params, s, kConvergedLimits);
  if (options.configure) options.configure(sim);
  const SceneGeometry geometry = options.geometry ? *options.geometry : scene_geometry(sim.rest());
  const auto guide_vertices = static_cast<std::ptrdiff_t>(sim.rest().rest_pos.size());
  Trajectory out;
  out.reserve(options.frames);
  for (uint32_t f = 0; f < options.frames; ++f) {
    const FramePlan plan = sim.advance(scene_frame(options.scene, f, geometry));
    if (options.sim_origins) options.sim_origins->push_back({plan.sim_origin[0], plan.sim_origin[1], plan.sim_origin[2]});
    out.emplace_back(sim.positions().begin(), sim.positions().begin() + guide_vertices);
  }
  if (median) *median = sim.median_strand_length();
  return out;
}

asset::HairAsset guide_prefix(const asset::HairAsset& a, uint32_t guides) {
  if (guides == 0 || guides > a.guide_count())
    throw std::invalid_argument("guide_prefix: " + std::to_string(guides) + " guides asked of an asset with " +
                                std::to_string(a.guide_count()));
  asset::HairAsset out = a;
  const size_t n = a.vertices_per_strand, k = a.follow_per_guide;
  const auto cut = [](auto& v, size_t count) {
    if (v.size() > count) v.resize(count);
  };
  cut(out.rest_positions, guides * n);
  cut(out.rest_lengths, guides * n);
  cut(out.rest_frames, guides * n);
  cut(out.rest_edge_local, guides * n);
  cut(out.guide_group, guides);
  cut(out.root_uv, guides);
  cut(out.bone_weights, guides);
  cut(out.follow_offsets, guides * k);
  return out;
}

std::vector<Vec3> at_arc_fractions(std::span<const Vec3> source, const ModelRest& src, const ModelRest& dst) {
  if (src.guide_count != dst.guide_count)
    throw std::invalid_argument("at_arc_fractions: the two rests have different guide counts");
  const size_t ns = src.vertices_per_strand, nd = dst.vertices_per_strand;
  std::vector<Vec3> out(size_t{dst.guide_count} * nd);
  for (size_t g = 0; g < dst.guide_count; ++g) {
    const double* fs = src.arc_fraction.data() + g * ns;
    size_t j = 0;  // source segment j .. j+1
    for (size_t v = 0; v < nd; ++v) {
      const double s = dst.arc_fraction[g * nd + v];
      while (j + 2 < ns && fs[j + 1] < s) ++j;
      const double span = fs[j + 1] - fs[j];
      const double t = span > 0 ? std::clamp((s - fs[j]) / span, 0.0, 1.0) : 0.0;
      out[g * nd + v] = source[g * ns + j] * (1.0 - t) + source[g * ns + j + 1] * t;
    }
  }
  return out;
}

}  // namespace tressvk::reference
