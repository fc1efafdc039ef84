// The baker's intermediate form: strands as variable-length double-precision polylines, root first, exactly as
// an importer read them (input units and axes). Every source (OBJ, .tfx, procedural) produces one of these and
// the same bake() pipeline turns it into a HairAsset.
#pragma once

#include <tressvk/asset.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tressvk::baker {

using Vec3 = std::array<double, 3>;

struct RawGroom {
  std::vector<Vec3> points;              // all strands back to back, root first
  std::vector<uint32_t> strand_begin{0};  // strand s is points[strand_begin[s] .. strand_begin[s+1])
  std::vector<uint32_t> strand_group;    // per strand, index into group_names
  std::vector<uint8_t> strand_pin_tip;   // per strand: 1 = the tip is held too (TressFX 3 bothEndsImmovable)
  std::vector<std::array<float, 2>> strand_uv;            // empty, or per strand (root UV)
  std::vector<asset::BoneInfluences> strand_bones;        // empty, or per strand
  std::vector<std::string> group_names;
  std::vector<std::string> bone_names;

  // Import statistics, carried into the bake report.
  uint64_t input_vertices = 0;      // vertices read from the source(s), including skipped strands
  uint64_t skipped_invalid = 0;     // strands dropped by --skip-invalid (branches, loops)
  uint64_t bone_influences_dropped = 0;  // influences beyond the 4 largest, dropped before renormalising
  uint64_t ignored_records = 0;     // OBJ records that are not hair (faces, normals, unknown keywords)

  size_t strand_count() const { return strand_begin.size() - 1; }
  // Adds a strand; group must index group_names.
  void add_strand(const Vec3* first, size_t count, uint32_t group, bool pin_tip = false);
  // Appends another groom (groups with the same name are merged). Bones and UVs are kept only when both have them.
  void append(const RawGroom& other);
};

}  // namespace tressvk::baker
