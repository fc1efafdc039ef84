// libFuzzer target: the TressFX .tfxbone importer (4.x and 5.x layouts). The weights are attached to a groom
// whose strand count the first two bytes give (little-endian, low 12 bits + 1: 1..4096), so that seeds made from real files
// (fuzz/make_seeds.py) match; the rest of the input is the .tfxbone file.
#include "fuzz_common.hpp"

#include <tressvk/baker/errors.hpp>
#include <tressvk/baker/import.hpp>

#include <cmath>

using namespace tressvk;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 2) return 0;
  const uint32_t strands = 1u + ((uint32_t{data[0]} | uint32_t{data[1]} << 8) & 0xFFFu);
  // One two-vertex strand per record; the groom is rebuilt only when the count changes.
  static baker::RawGroom cached;
  static uint32_t cached_strands = 0;
  if (cached_strands != strands) {
    cached = baker::RawGroom{};
    cached.group_names = {"g"};
    for (uint32_t s = 0; s < strands; ++s) {
      const baker::Vec3 p[2] = {{double(s), 0, 0}, {double(s), 0.1, 0}};
      cached.add_strand(p, 2, 0);
    }
    cached_strands = strands;
  }
  baker::RawGroom g = cached;
  try {
    baker::apply_tfxbone_bytes(g, fuzz::as_bytes(data + 2, size - 2), "fuzz.tfxbone");
    if (g.strand_bones.size() != g.strand_count()) fuzz::finding("strand_bones has the wrong size");
    for (const auto& b : g.strand_bones) {
      double sum = 0;
      for (size_t k = 0; k < asset::kMaxBoneInfluences; ++k) {
        if (!(b.weight[k] >= 0.0f) || !std::isfinite(b.weight[k])) fuzz::finding("a bad bone weight");
        if (b.weight[k] > 0 && b.bone[k] >= g.bone_names.size()) fuzz::finding("a bone index out of range");
        sum += b.weight[k];
      }
      if (std::abs(sum - 1.0) > 1e-4) fuzz::finding("bone weights do not sum to 1: " + std::to_string(sum));
    }
  } catch (const baker::InputError&) {
  }
  return 0;
}
