// Shared fixtures of the reference tests.
#pragma once

#include <string>
#include <vector>

#include <tressvk/asset.hpp>
#include <tressvk/baker/procedural.hpp>
#include <tressvk/reference/metrics.hpp>
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

// The same groom `s` times larger: every length in the asset scaled (positions, origin, rest lengths, rest edges,
// follow offsets); directions, frames and pinning unchanged.
inline tressvk::asset::HairAsset scaled_groom(tressvk::asset::HairAsset a, double s) {
  for (double& o : a.origin) o *= s;
  for (auto& p : a.rest_positions)
    for (size_t k = 0; k < 3; ++k) p[k] = static_cast<float>(static_cast<double>(p[k]) * s);
  for (float& l : a.rest_lengths) l = static_cast<float>(static_cast<double>(l) * s);
  for (auto& e : a.rest_edge_local)
    for (size_t k = 0; k < 3; ++k) e[k] = static_cast<float>(static_cast<double>(e[k]) * s);
  for (auto& f : a.follow_offsets)
    for (size_t k = 0; k < 3; ++k) f[k] = static_cast<float>(static_cast<double>(f[k]) * s);
  return a;
}

// What a scene becomes at `s` times the size: every parameter that is a length or a speed scaled with it.
inline void scale_inputs(double s, TvkSimParams& p, TvkSimSettings& settings) {
  p.max_speed = static_cast<float>(p.max_speed * s);
  p.vsp_threshold = static_cast<float>(p.vsp_threshold * s);
  for (float& g : settings.gravity) g = static_cast<float>(g * s);
}

}  // namespace tvk_test
