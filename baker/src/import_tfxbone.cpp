// TressFX .tfxbone bone weights: the 4.x layout (fixed 4 influences per strand) and the 5.x layout (counted),
// which share a bone table and have no version field.
#include "binary_cursor.hpp"
#include "vec_math.hpp"

#include <tressvk/baker/import.hpp>

#include <algorithm>

namespace tressvk::baker {

namespace {

struct BoneRecords {
  std::vector<asset::BoneInfluences> bones;
  uint64_t dropped = 0;
};

// Per-strand records of either layout; must use up the file exactly.
BoneRecords parse_bone_records(BinaryCursor& c, bool layout4, int32_t strand_count, int32_t bone_count) {
  BoneRecords out;
  out.bones.resize(static_cast<size_t>(strand_count));
  std::vector<uint8_t> assigned(out.bones.size(), 0);
  std::vector<std::pair<float, uint32_t>> infl;
  const char* layout = layout4 ? " (4.x layout)" : " (5.x layout)";
  for (int32_t s = 0; s < strand_count; ++s) {
    const int32_t index = c.get<int32_t>("strand index");
    if (index < 0 || index >= strand_count)
      c.fail("strand record " + std::to_string(s) + ": strand index " + std::to_string(index) + " out of range" + layout);
    const int32_t count = layout4 ? 4 : c.get<int32_t>("influence count");
    if (count < 0 || count > 64)
      c.fail("strand " + std::to_string(index) + ": influence count " + std::to_string(count) + " out of range" + layout);
    infl.clear();
    for (int32_t k = 0; k < count; ++k) {
      const int32_t bone = c.get<int32_t>("bone index");
      const float w = c.get<float>("bone weight");
      if (!std::isfinite(w) || w < 0)
        c.fail("strand " + std::to_string(index) + ": weight " + std::to_string(w) + " is not finite and >= 0" + layout);
      if (w == 0) continue;  // unused slot (4.x pads with zero weights, often with bone index -1)
      if (bone < 0 || bone >= bone_count)
        c.fail("strand " + std::to_string(index) + ": bone index " + std::to_string(bone) + " out of range" + layout);
      infl.emplace_back(w, static_cast<uint32_t>(bone));
    }
    if (infl.empty()) c.fail("strand " + std::to_string(index) + ": no bone influence with a positive weight" + layout);
    if (assigned[static_cast<size_t>(index)]) c.fail("strand " + std::to_string(index) + " has two records" + layout);
    assigned[static_cast<size_t>(index)] = 1;
    // Largest first; equal weights by bone index, so the result never depends on the file's slot order.
    std::sort(infl.begin(), infl.end(),
              [](const auto& x, const auto& y) { return x.first != y.first ? x.first > y.first : x.second < y.second; });
    if (infl.size() > asset::kMaxBoneInfluences) {
      out.dropped += infl.size() - asset::kMaxBoneInfluences;
      infl.resize(asset::kMaxBoneInfluences);
    }
    double sum = 0;
    for (const auto& i : infl) sum += i.first;
    auto& bones = out.bones[static_cast<size_t>(index)];
    for (size_t k = 0; k < infl.size(); ++k) {
      bones.bone[k] = infl[k].second;
      bones.weight[k] = static_cast<float>(infl[k].first / sum);
    }
  }
  if (c.remaining() != 0)
    c.fail(std::to_string(c.remaining()) + " unexpected bytes after the last strand record" + layout);
  return out;
}

}  // namespace

void apply_tfxbone_bytes(RawGroom& groom, std::span<const std::byte> b, std::string_view name) {
  BinaryCursor c(b, name);
  if (b.empty()) c.fail("empty file");
  const int32_t bone_count = c.get<int32_t>("numBones");
  // Each bone entry takes at least 9 bytes, so a larger count cannot be right (and must not be allocated).
  if (bone_count <= 0 || static_cast<uint64_t>(bone_count) > c.remaining() / 9)
    c.fail("field numBones = " + std::to_string(bone_count) + " is not a plausible bone count");
  std::vector<std::string> names(static_cast<size_t>(bone_count));
  std::vector<uint8_t> named(names.size(), 0);
  for (int32_t i = 0; i < bone_count; ++i) {
    const int32_t index = c.get<int32_t>("bone index");
    const int32_t len = c.get<int32_t>("bone name length");
    if (index < 0 || index >= bone_count) c.fail("bone " + std::to_string(i) + ": index " + std::to_string(index) + " out of range");
    if (len <= 0 || static_cast<size_t>(len) > c.remaining() || len > 4096)
      c.fail("bone " + std::to_string(i) + ": name length " + std::to_string(len) + " is invalid");
    std::string s(reinterpret_cast<const char*>(b.data() + c.pos()), static_cast<size_t>(len));
    c.skip(static_cast<size_t>(len));
    s = s.substr(0, s.find('\0'));
    if (named[static_cast<size_t>(index)]) c.fail("bone index " + std::to_string(index) + " appears twice");
    named[static_cast<size_t>(index)] = 1;
    names[static_cast<size_t>(index)] = s;
  }
  const int32_t strand_count = c.get<int32_t>("numStrands");
  if (strand_count < 0 || static_cast<uint64_t>(strand_count) != groom.strand_count())
    c.fail("field numStrands = " + std::to_string(strand_count) + " but the hair has " +
           std::to_string(groom.strand_count()) + " strands");
  // The two layouts have no version field. 4.x is exactly 36 bytes per strand; when the size fits, try it first
  // and fall back to 5.x if the records do not make sense as 4.x (a 5.x file can have that size by chance).
  BoneRecords result;
  if (c.remaining() == 36ull * static_cast<uint64_t>(strand_count)) {
    BinaryCursor c4 = c;
    try {
      result = parse_bone_records(c4, true, strand_count, bone_count);
    } catch (const InputError& error4) {
      try {
        BinaryCursor c5 = c;
        result = parse_bone_records(c5, false, strand_count, bone_count);
      } catch (const InputError&) {
        throw error4;
      }
    }
  } else {
    result = parse_bone_records(c, false, strand_count, bone_count);
  }
  groom.bone_influences_dropped += result.dropped;
  groom.bone_names = std::move(names);
  groom.strand_bones = std::move(result.bones);
}

void apply_tfxbone(RawGroom& groom, const std::filesystem::path& path) {
  const auto bytes = read_binary_file(path);
  apply_tfxbone_bytes(groom, bytes, path.string());
}

}  // namespace tressvk::baker
