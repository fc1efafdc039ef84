// Shared fixtures of the reference tests.
#pragma once

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include <tressvk/asset.hpp>
#include <tressvk/baker/procedural.hpp>
#include <tressvk/reference/metrics.hpp>
#include <tressvk/reference/scaling.hpp>
#include <tressvk/reference/scenes.hpp>
#include <tressvk/reference/simulator.hpp>

namespace tvk_test {

using namespace tressvk::reference;

inline tressvk::asset::HairAsset groom(const std::string& name, uint32_t guides = 64, uint32_t follows = 0,
                                       uint32_t n = 0) {
  tressvk::baker::BuiltinGroomOptions o;
  o.guide_count = guides;
  o.follow_per_guide = follows;
  o.vertices_per_strand = n;
  return tressvk::baker::make_builtin_groom(name, o);
}

inline TvkSimParams default_params() {
  TvkSimParams p = TVK_SIM_PARAMS_DEFAULT_INIT;
  return p;
}

inline TvkSimSettings default_settings() {
  TvkSimSettings s = TVK_SIM_SETTINGS_DEFAULT_INIT;
  return s;
}

inline Simulator make_sim(const tressvk::asset::HairAsset& a, const TvkSimParams& p = default_params(),
                          const TvkSimSettings& s = default_settings()) {
  return Simulator(a, std::span<const TvkSimParams>(&p, 1), s);
}

// Largest distance between two position lists divided by the median strand length.
inline double max_rel(std::span<const Vec3> a, std::span<const Vec3> b, double median) {
  return position_error(a, b, median).max_rel;
}

// `frames` frames of `settle` without gravity (params `p`, and `model` where given): the largest distance of a guide
// vertex from the rest pose of the first step, relative to the median strand length (without gravity the rest pose
// is a fixed point).
inline double drift_at_rest(const tressvk::asset::HairAsset& a, uint32_t frames, const TvkSimParams& p = default_params(),
                            std::optional<Simulator::LengthModel> model = std::nullopt) {
  TvkSimSettings s = default_settings();
  s.gravity[1] = 0.0f;
  Simulator sim = make_sim(a, p, s);
  if (model) sim.set_model(*model);
  const SceneGeometry geo = scene_geometry(sim.rest());
  const FramePlan first = sim.advance(scene_frame("settle", 0, geo));
  std::vector<Vec3> rest;
  for (size_t i = 0; i < sim.rest().rest_pos.size(); ++i) rest.push_back(sim.skinned_rest(first.steps[0], i));
  for (uint32_t f = 1; f < frames; ++f) sim.advance(scene_frame("settle", f, geo));
  const auto now = sim.positions();
  return max_rel(now.first(rest.size()), rest, sim.median_strand_length());
}

// The same groom `s` times larger, and the scene's inputs with it (tressvk/reference/scaling.hpp, shared with the
// hard-case suite of tressvk-bench).
using tressvk::reference::scale_inputs;
using tressvk::reference::scaled_groom;

// The asset with only the listed guides (comma-separated indices), their follows, groups and bone weights; `median`
// receives the whole groom's median strand length (short strands are carried rigidly by it: TvkSimParams::rigid_below).
// Strands do not interact, so a few of a large groom's guides can be studied alone in a fraction of the time.
inline tressvk::asset::HairAsset only_guides(const tressvk::asset::HairAsset& a, const std::string& list, double& median) {
  const uint32_t n = a.vertices_per_strand, k = a.follow_per_guide;
  std::vector<double> lengths;
  for (uint32_t g = 0; g < a.guide_count(); ++g) {
    double l = 0;
    for (uint32_t v = 0; v + 1 < n; ++v) l += a.rest_lengths[size_t{g} * n + v];
    lengths.push_back(l);
  }
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2), lengths.end());
  median = lengths[lengths.size() / 2];
  tressvk::asset::HairAsset o = a;
  o.rest_positions.clear(); o.rest_lengths.clear(); o.rest_frames.clear(); o.rest_edge_local.clear();
  o.guide_group.clear(); o.root_uv.clear(); o.bone_weights.clear(); o.follow_offsets.clear();
  size_t at = 0;
  while (at < list.size()) {
    const size_t comma = std::min(list.find(',', at), list.size());
    const uint32_t g = static_cast<uint32_t>(std::stoul(list.substr(at, comma - at)));
    at = comma + 1;
    if (g >= a.guide_count()) continue;
    const size_t b = size_t{g} * n;
    for (uint32_t v = 0; v < n; ++v) {
      o.rest_positions.push_back(a.rest_positions[b + v]);
      o.rest_lengths.push_back(a.rest_lengths[b + v]);
      o.rest_frames.push_back(a.rest_frames[b + v]);
      o.rest_edge_local.push_back(a.rest_edge_local[b + v]);
    }
    if (!a.guide_group.empty()) o.guide_group.push_back(a.guide_group[g]);
    if (!a.root_uv.empty()) o.root_uv.push_back(a.root_uv[g]);
    if (!a.bone_weights.empty()) o.bone_weights.push_back(a.bone_weights[g]);
    for (uint32_t f = 0; f < k; ++f) o.follow_offsets.push_back(a.follow_offsets[size_t{g} * k + f]);
  }
  return o;
}

}  // namespace tvk_test
