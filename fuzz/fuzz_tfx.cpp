// libFuzzer target: the TressFX .tfx importer (v3 and v4 layouts).
#include "fuzz_common.hpp"

#include <tressvk/baker/errors.hpp>
#include <tressvk/baker/import.hpp>

#include <cmath>

using namespace tressvk;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const baker::RawGroom g = baker::import_tfx_bytes(fuzz::as_bytes(data, size), "fuzz.tfx");
    if (g.strand_begin.back() != g.points.size()) fuzz::finding("strand_begin does not end at the point count");
    if (!g.strand_uv.empty() && g.strand_uv.size() != g.strand_count()) fuzz::finding("strand_uv has the wrong size");
    // Every vertex came from the file: the points fit in the bytes that were given (16 bytes or 12 each).
    if (g.points.size() > size / 12) fuzz::finding("more points than the file can hold");
    for (const auto& p : g.points)
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) fuzz::finding("non-finite point");
  } catch (const baker::InputError&) {
  }
  return 0;
}
