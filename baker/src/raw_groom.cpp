#include <tressvk/baker/raw_groom.hpp>

#include <algorithm>

namespace tressvk::baker {

void RawGroom::add_strand(const Vec3* first, size_t count, uint32_t group, bool pin_tip) {
  points.insert(points.end(), first, first + count);
  strand_begin.push_back(static_cast<uint32_t>(points.size()));
  strand_group.push_back(group);
  strand_pin_tip.push_back(pin_tip ? 1 : 0);
}

void RawGroom::append(const RawGroom& other) {
  const bool keep_uv = (strand_count() == 0 || !strand_uv.empty()) && !other.strand_uv.empty();
  const bool keep_bones = (strand_count() == 0 || !strand_bones.empty()) && !other.strand_bones.empty();
  if (!keep_uv) strand_uv.clear();
  if (!keep_bones) {
    strand_bones.clear();
    bone_names.clear();
  }
  std::vector<uint32_t> group_map;
  for (const auto& name : other.group_names) {
    auto it = std::find(group_names.begin(), group_names.end(), name);
    if (it == group_names.end()) {
      group_names.push_back(name);
      group_map.push_back(static_cast<uint32_t>(group_names.size() - 1));
    } else {
      group_map.push_back(static_cast<uint32_t>(it - group_names.begin()));
    }
  }
  // Bone indices of the appended groom are shifted past ours (bone tables are per source file).
  const auto bone_shift = static_cast<uint32_t>(bone_names.size());
  if (keep_bones) bone_names.insert(bone_names.end(), other.bone_names.begin(), other.bone_names.end());
  for (size_t s = 0; s < other.strand_count(); ++s) {
    add_strand(other.points.data() + other.strand_begin[s], other.strand_begin[s + 1] - other.strand_begin[s],
               group_map[other.strand_group[s]], other.strand_pin_tip[s] != 0);
    if (keep_uv) strand_uv.push_back(other.strand_uv[s]);
    if (keep_bones) {
      auto b = other.strand_bones[s];
      for (size_t k = 0; k < asset::kMaxBoneInfluences; ++k)
        if (b.weight[k] > 0) b.bone[k] += bone_shift;
      strand_bones.push_back(b);
    }
  }
  input_vertices += other.input_vertices;
  skipped_invalid += other.skipped_invalid;
  bone_influences_dropped += other.bone_influences_dropped;
  ignored_records += other.ignored_records;
}

}  // namespace tressvk::baker
