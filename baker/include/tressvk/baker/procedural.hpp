// Built-in procedural grooms for tests and benchmarks. They go through the same bake() pipeline as imported
// hair (resampling, rest frames, follows, level-of-detail order), so they exercise exactly what real assets do.
//
// All are grown from the upper half (y > 0) of a head sphere of radius 0.1 m centred at the origin, roots on a
// Fibonacci spiral (even coverage) with a seeded rotation:
//   "straight": straight strands 0.15 m long along the scalp normal;
//   "curly":    helices around the scalp normal, radius 1 cm, pitch 2 cm, 0.15 m tall (about 0.5 m of hair);
//   "long128":  128 vertices, 0.5 m long, leaving along the normal and bending down under their own weight.
#pragma once

#include <tressvk/asset.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tressvk::baker {

struct BuiltinGroomOptions {
  uint32_t guide_count = 1024;
  uint32_t follow_per_guide = 0;
  uint64_t seed = 1;
  uint32_t vertices_per_strand = 0;  // 0: the groom's default (32; 128 for "long128")
};

std::vector<std::string> builtin_groom_names();

// Throws std::invalid_argument for an unknown name or out-of-range options.
asset::HairAsset make_builtin_groom(std::string_view name, const BuiltinGroomOptions& options = {});

}  // namespace tressvk::baker
