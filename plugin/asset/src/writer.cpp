// Serialises a HairAsset into .tvkhair bytes, and writes files atomically (temporary file + rename).
#include "format.hpp"

#include <tressvk/asset_io.hpp>

#include <cerrno>
#include <cstdio>
#include <fstream>
#include <system_error>
#include <unistd.h>

namespace tressvk::asset {
namespace {

using namespace format;

// A section to write: plain arrays are viewed in place (no copy of a 100 MB asset), built ones are owned.
struct PendingSection {
  uint32_t id;
  uint32_t stride;
  uint64_t count;
  std::vector<std::byte> owned;
  std::span<const std::byte> bytes;
};

template <typename T>
PendingSection raw_section(uint32_t id, const std::vector<T>& v) {
  return {id, static_cast<uint32_t>(sizeof(T)), v.size(), {}, std::as_bytes(std::span(v))};
}

PendingSection owned_section(uint32_t id, uint32_t stride, uint64_t count, std::vector<std::byte> bytes) {
  PendingSection s{id, stride, count, std::move(bytes), {}};
  s.bytes = s.owned;
  return s;
}

class ByteWriter {
 public:
  template <typename T>
  void put(T v) {
    const size_t at = out_.size();
    out_.resize(at + sizeof(T));
    std::memcpy(out_.data() + at, &v, sizeof(T));
  }
  void put_string(const std::string& s) {
    put(static_cast<uint32_t>(s.size()));
    const size_t at = out_.size();
    out_.resize(at + s.size());
    if (!s.empty()) std::memcpy(out_.data() + at, s.data(), s.size());
  }
  std::vector<std::byte> take() { return std::move(out_); }

 private:
  std::vector<std::byte> out_;
};

PendingSection meta_section(const HairAsset& a) {
  ByteWriter w;
  w.put(a.vertices_per_strand);
  w.put(a.follow_per_guide);
  w.put(a.guide_count());
  w.put(a.tip_separation);
  for (double o : a.origin) w.put(o);
  w.put(static_cast<uint32_t>(a.groups.size()));
  for (const auto& g : a.groups) w.put_string(g.name);
  w.put(static_cast<uint32_t>(a.bone_names.size()));
  for (const auto& b : a.bone_names) w.put_string(b);
  w.put_string(a.bake_settings);
  auto bytes = w.take();
  const uint64_t n = bytes.size();
  return owned_section(kMeta, 1, n, std::move(bytes));
}

PendingSection bone_section(const std::vector<BoneInfluences>& bones) {
  std::vector<std::byte> bytes(bones.size() * kBoneRecordSize);
  std::span<std::byte> out(bytes);
  for (size_t i = 0; i < bones.size(); ++i) {
    for (size_t k = 0; k < kMaxBoneInfluences; ++k) {
      store(out, i * kBoneRecordSize + 4 * k, bones[i].bone[k]);
      store(out, i * kBoneRecordSize + 16 + 4 * k, bones[i].weight[k]);
    }
  }
  return owned_section(kBoneWeights, kBoneRecordSize, bones.size(), std::move(bytes));
}

}  // namespace

std::vector<std::byte> write(const HairAsset& a, FileInfo* info_out) {
  std::vector<PendingSection> sections;
  sections.push_back(meta_section(a));
  sections.push_back(raw_section(kRestPositions, a.rest_positions));
  sections.push_back(raw_section(kRestLengths, a.rest_lengths));
  sections.push_back(raw_section(kRestFrames, a.rest_frames));
  sections.push_back(raw_section(kRestEdges, a.rest_edge_local));
  sections.push_back(raw_section(kGuideGroups, a.guide_group));
  if (!a.root_uv.empty()) sections.push_back(raw_section(kRootUv, a.root_uv));
  if (!a.bone_weights.empty()) sections.push_back(bone_section(a.bone_weights));
  sections.push_back(raw_section(kFollowOffsets, a.follow_offsets));

  const uint64_t table_offset = kHeaderSize;
  uint64_t cursor = align_up(table_offset + sections.size() * kTableEntrySize);
  std::vector<uint64_t> offsets;
  for (const auto& s : sections) {
    offsets.push_back(cursor);
    cursor = align_up(cursor + s.bytes.size());
  }
  const uint64_t file_size = cursor;

  if (info_out) *info_out = FileInfo{};
  std::vector<std::byte> out(file_size, std::byte{0});  // padding stays zero; the reader insists on it
  std::span<std::byte> o(out);
  std::memcpy(out.data(), kMagic, sizeof(kMagic));
  store(o, kOffMajor, kFormatMajor);
  store(o, kOffMinor, kFormatMinor);
  store(o, kOffHeaderSize, kHeaderSize);
  store(o, kOffFileSize, file_size);
  store(o, kOffSectionCount, static_cast<uint32_t>(sections.size()));
  store(o, kOffFlags, uint32_t{0});
  store(o, kOffTableOffset, table_offset);
  store(o, kOffEntrySize, kTableEntrySize);
  for (size_t i = 0; i < sections.size(); ++i) {
    const auto& s = sections[i];
    const size_t e = table_offset + i * kTableEntrySize;
    store(o, e + kEntId, s.id);
    store(o, e + kEntOffset, offsets[i]);
    store(o, e + kEntSize, static_cast<uint64_t>(s.bytes.size()));
    store(o, e + kEntStride, s.stride);
    store(o, e + kEntCount, s.count);
    const uint32_t crc = crc32(s.bytes);
    store(o, e + kEntCrc, crc);
    if (info_out)
      info_out->sections.push_back({fourcc_name(s.id), s.id, offsets[i], s.bytes.size(), s.stride, s.count, crc, crc, true});
    if (!s.bytes.empty()) std::memcpy(out.data() + offsets[i], s.bytes.data(), s.bytes.size());
  }
  store(o, kOffTableCrc, crc32(o.subspan(table_offset, sections.size() * kTableEntrySize)));
  store(o, kOffHeaderCrc, crc32(o.subspan(0, kHeaderSize)));  // computed with its own field still zero
  if (info_out) {
    info_out->major = kFormatMajor;
    info_out->minor = kFormatMinor;
    info_out->file_size = file_size;
    info_out->checksums_ok = true;
  }
  return out;
}

std::string write_file(const std::filesystem::path& path, std::span<const std::byte> bytes) {
  // Same directory as the target, so rename() is atomic; the pid keeps parallel bakes apart.
  std::filesystem::path tmp = path;
  tmp += ".tmp" + std::to_string(static_cast<long>(::getpid()));
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) return "cannot create " + tmp.string() + ": " + std::generic_category().message(errno);
    f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    f.flush();
    if (!f) {
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);
      return "cannot write " + tmp.string() + ": " + std::generic_category().message(errno);
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    return "cannot rename " + tmp.string() + " to " + path.string() + ": " + ec.message();
  }
  return {};
}

}  // namespace tressvk::asset
