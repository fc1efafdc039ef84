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

namespace {

// Where everything goes: the header and table bytes (zero-padded up to the first section), and the sections with
// their offsets. write() assembles it in memory; write_file() streams it, so a 100 MB asset is never copied.
struct Layout {
  std::vector<PendingSection> sections;
  std::vector<uint64_t> offsets;
  std::vector<std::byte> head;
  uint64_t file_size = 0;
};

Layout make_layout(const HairAsset& a, FileInfo* info_out) {
  Layout l;
  auto& sections = l.sections;
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
  for (const auto& sec : sections) {
    l.offsets.push_back(cursor);
    cursor = align_up(cursor + sec.bytes.size());
  }
  l.file_size = cursor;

  if (info_out) *info_out = FileInfo{};
  l.head.assign(l.offsets.front(), std::byte{0});  // padding stays zero; the reader insists on it
  std::span<std::byte> o(l.head);
  std::memcpy(o.data(), kMagic, sizeof(kMagic));
  store(o, kOffMajor, kFormatMajor);
  store(o, kOffMinor, kFormatMinor);
  store(o, kOffHeaderSize, kHeaderSize);
  store(o, kOffFileSize, l.file_size);
  store(o, kOffSectionCount, static_cast<uint32_t>(sections.size()));
  store(o, kOffFlags, uint32_t{0});
  store(o, kOffTableOffset, table_offset);
  store(o, kOffEntrySize, kTableEntrySize);
  for (size_t i = 0; i < sections.size(); ++i) {
    const auto& sec = sections[i];
    const size_t e = table_offset + i * kTableEntrySize;
    store(o, e + kEntId, sec.id);
    store(o, e + kEntOffset, l.offsets[i]);
    store(o, e + kEntSize, static_cast<uint64_t>(sec.bytes.size()));
    store(o, e + kEntStride, sec.stride);
    store(o, e + kEntCount, sec.count);
    const uint32_t crc = crc32(sec.bytes);
    store(o, e + kEntCrc, crc);
    if (info_out)
      info_out->sections.push_back(
          {fourcc_name(sec.id), sec.id, l.offsets[i], sec.bytes.size(), sec.stride, sec.count, crc, crc, true});
  }
  store(o, kOffTableCrc, crc32(o.subspan(table_offset, sections.size() * kTableEntrySize)));
  store(o, kOffHeaderCrc, crc32(o.subspan(0, kHeaderSize)));  // computed with its own field still zero
  if (info_out) {
    info_out->major = kFormatMajor;
    info_out->minor = kFormatMinor;
    info_out->file_size = l.file_size;
    info_out->checksums_ok = true;
  }
  return l;
}

// Emits the file through `sink(span)` in order: head, then each section followed by its zero padding.
template <typename Sink>
void emit(const Layout& l, Sink&& sink) {
  static constexpr std::byte kZeros[kAlignment] = {};
  sink(std::span<const std::byte>(l.head));
  for (size_t i = 0; i < l.sections.size(); ++i) {
    sink(l.sections[i].bytes);
    const uint64_t end = l.offsets[i] + l.sections[i].bytes.size();
    const uint64_t next = i + 1 < l.sections.size() ? l.offsets[i + 1] : l.file_size;
    sink(std::span<const std::byte>(kZeros, static_cast<size_t>(next - end)));
  }
}

std::filesystem::path temp_path_for(const std::filesystem::path& path) {
  // Same directory as the target, so rename() is atomic; the pid keeps parallel bakes apart.
  std::filesystem::path tmp = path;
  tmp += ".tmp" + std::to_string(static_cast<long>(::getpid()));
  return tmp;
}

template <typename Emit>
std::string write_atomically(const std::filesystem::path& path, Emit&& emit_into) {
  const std::filesystem::path tmp = temp_path_for(path);
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) return "cannot create " + tmp.string() + ": " + std::generic_category().message(errno);
    emit_into([&](std::span<const std::byte> b) {
      if (!b.empty()) f.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
    });
    f.flush();
    if (!f) {
      const std::string reason = std::generic_category().message(errno);
      f.close();
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);
      return "cannot write " + tmp.string() + ": " + reason;
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

}  // namespace

std::vector<std::byte> write(const HairAsset& a, FileInfo* info_out) {
  const Layout l = make_layout(a, info_out);
  std::vector<std::byte> out;
  out.reserve(l.file_size);
  emit(l, [&](std::span<const std::byte> b) { out.insert(out.end(), b.begin(), b.end()); });
  return out;
}

std::string write_file(const std::filesystem::path& path, const HairAsset& asset, FileInfo* info_out) {
  try {
    const Layout l = make_layout(asset, info_out);
    return write_atomically(path, [&](auto&& sink) { emit(l, sink); });
  } catch (const std::exception& ex) {
    return "cannot write " + path.string() + ": " + ex.what();
  }
}

std::string write_file(const std::filesystem::path& path, std::span<const std::byte> bytes) {
  try {
    return write_atomically(path, [&](auto&& sink) { sink(bytes); });
  } catch (const std::exception& ex) {
    return "cannot write " + path.string() + ": " + ex.what();
  }
}

}  // namespace tressvk::asset
