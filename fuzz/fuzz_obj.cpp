// libFuzzer target: the OBJ polyline importer (text -> RawGroom), including the scalp-orientation path.
// Two bits of the input size pick the options, so one corpus reaches every combination.
#include "fuzz_common.hpp"

#include <tressvk/baker/errors.hpp>
#include <tressvk/baker/import.hpp>

#include <cmath>
#include <string_view>

using namespace tressvk;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  baker::ObjImportOptions options;
  options.root_from = (size & 1) ? baker::RootFrom::kFaces : baker::RootFrom::kIndex;
  options.skip_invalid = (size & 2) != 0;
  const bool want_faces = (size & 4) != 0;
  baker::ScalpMesh faces;
  try {
    const baker::RawGroom g = baker::import_obj_text(std::string_view(reinterpret_cast<const char*>(data), size),
                                                     "fuzz.obj", options, want_faces ? &faces : nullptr);
    // What the importer accepted is well formed: strand ranges cover the points, every point is finite.
    if (g.strand_begin.empty() || g.strand_begin.back() != g.points.size())
      fuzz::finding("strand_begin does not end at the point count");
    if (g.strand_group.size() != g.strand_count()) fuzz::finding("strand_group has the wrong size");
    for (size_t s = 0; s < g.strand_count(); ++s) {
      if (g.strand_begin[s + 1] < g.strand_begin[s] + 2) fuzz::finding("a strand with fewer than 2 vertices");
      if (g.strand_group[s] >= g.group_names.size()) fuzz::finding("a strand group index out of range");
    }
    for (const auto& p : g.points)
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) fuzz::finding("non-finite point");
    for (const auto& t : faces.triangles)
      for (uint32_t i : t)
        if (i >= faces.vertices.size()) fuzz::finding("a scalp triangle index out of range");
  } catch (const baker::InputError&) {
  }
  return 0;
}
