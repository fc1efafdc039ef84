// A groom and its scene at another size (the tests' and the hard-case suite's 1/100 and 100x grooms): every length in
// the asset scaled, and every parameter that is a length or a speed scaled with it, so the scaled groom should move
// the same, in proportion.
#pragma once

#include <tressvk/asset.hpp>

#include "tressvk/sim_types.h"

namespace tressvk::reference {

// The same groom `s` times larger: every length in the asset scaled (positions, origin, rest lengths, rest edges,
// follow offsets); directions, frames and pinning unchanged.
inline asset::HairAsset scaled_groom(asset::HairAsset a, double s) {
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

}  // namespace tressvk::reference
