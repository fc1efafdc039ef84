// Reads .tvkhair bytes into a HairAsset. Never throws: every check returns a message naming what is wrong.
#include "format.hpp"

#include <tressvk/asset_io.hpp>

#include <algorithm>
#include <fstream>
#include <new>
#include <optional>

namespace tressvk::asset {
namespace {

using namespace format;

ReadResult fail(std::string message, FileInfo info = {}) {
  ReadResult r;
  r.status = ReadStatus::kInvalid;
  r.error = std::move(message);
  r.info = std::move(info);
  return r;
}

// Bounded cursor over the META section.
class ByteReader {
 public:
  explicit ByteReader(std::span<const std::byte> b) : bytes_(b) {}
  template <typename T>
  bool get(T& v) {
    if (bytes_.size() - pos_ < sizeof(T)) return false;
    v = load<T>(bytes_, pos_);
    pos_ += sizeof(T);
    return true;
  }
  bool get_string(std::string& s) {
    uint32_t n = 0;
    if (!get(n) || bytes_.size() - pos_ < n) return false;
    s.assign(reinterpret_cast<const char*>(bytes_.data() + pos_), n);
    pos_ += n;
    return true;
  }

 private:
  std::span<const std::byte> bytes_;
  size_t pos_ = 0;
};

const SectionInfo* find(const FileInfo& info, uint32_t id) {
  for (const auto& s : info.sections)
    if (s.id == id) return &s;
  return nullptr;
}

// Copies a section of plain elements after checking its stride and element count.
template <typename T>
std::string copy_section(std::span<const std::byte> bytes, const SectionInfo* s, uint64_t expected_count,
                         std::vector<T>& out) {
  if (s->stride != sizeof(T))
    return "section " + s->name + ": element stride " + std::to_string(s->stride) + ", expected " +
           std::to_string(sizeof(T));
  if (s->count != expected_count)
    return "section " + s->name + ": " + std::to_string(s->count) + " elements, expected " +
           std::to_string(expected_count) + " from META";
  out.resize(static_cast<size_t>(expected_count));
  if (expected_count) std::memcpy(out.data(), bytes.data() + s->offset, static_cast<size_t>(s->size));
  return {};
}

ReadResult read_impl(std::span<const std::byte> bytes) {
  ReadResult r = inspect(bytes);
  if (!r.ok()) return r;
  const FileInfo& info = r.info;
  for (const auto& s : info.sections) {
    if (!s.crc_ok)
      return fail("section " + s.name + ": checksum mismatch (stored " + std::to_string(s.stored_crc) +
                      ", computed " + std::to_string(s.actual_crc) + "): the file is damaged",
                  info);
  }
  for (uint32_t id : {kMeta, kRestPositions, kRestLengths, kRestFrames, kRestEdges, kGuideGroups, kFollowOffsets}) {
    if (!find(info, id)) return fail("required section " + fourcc_name(id) + " is missing", info);
  }

  HairAsset a;
  const SectionInfo* meta = find(info, kMeta);
  ByteReader m(bytes.subspan(static_cast<size_t>(meta->offset), static_cast<size_t>(meta->size)));
  uint32_t guides = 0, group_count = 0, bone_count = 0;
  if (!m.get(a.vertices_per_strand) || !m.get(a.follow_per_guide) || !m.get(guides) || !m.get(a.tip_separation) ||
      !m.get(a.origin[0]) || !m.get(a.origin[1]) || !m.get(a.origin[2]))
    return fail("section META: truncated before the counts and origin", info);
  if (a.vertices_per_strand < kMinVerticesPerStrand || a.vertices_per_strand > kMaxVerticesPerStrand)
    return fail("section META: vertices_per_strand " + std::to_string(a.vertices_per_strand) + " outside " +
                    std::to_string(kMinVerticesPerStrand) + ".." + std::to_string(kMaxVerticesPerStrand),
                info);
  if (!m.get(group_count)) return fail("section META: truncated before group_count", info);
  // Each name costs at least 4 bytes, so a count larger than the section is damage, not a reason to allocate.
  if (group_count > meta->size / 4) return fail("section META: group_count " + std::to_string(group_count) +
                                                    " larger than the section allows", info);
  a.groups.resize(group_count);
  for (uint32_t i = 0; i < group_count; ++i)
    if (!m.get_string(a.groups[i].name))
      return fail("section META: group name " + std::to_string(i) + " truncated", info);
  if (!m.get(bone_count)) return fail("section META: truncated before bone_count", info);
  if (bone_count > meta->size / 4) return fail("section META: bone_count " + std::to_string(bone_count) +
                                                   " larger than the section allows", info);
  a.bone_names.resize(bone_count);
  for (uint32_t i = 0; i < bone_count; ++i)
    if (!m.get_string(a.bone_names[i]))
      return fail("section META: bone name " + std::to_string(i) + " truncated", info);
  if (!m.get_string(a.bake_settings)) return fail("section META: bake settings truncated", info);
  // Later minor versions may append fields to META; they are ignored here.

  const uint64_t n = a.vertices_per_strand;
  const uint64_t vertex_count = static_cast<uint64_t>(guides) * n;
  const uint64_t follow_count = static_cast<uint64_t>(guides) * a.follow_per_guide;
  // Sections were bounds-checked against the file by inspect(), so counts that match them are affordable.
  std::string e;
  if (!(e = copy_section(bytes, find(info, kRestPositions), vertex_count, a.rest_positions)).empty() ||
      !(e = copy_section(bytes, find(info, kRestLengths), vertex_count, a.rest_lengths)).empty() ||
      !(e = copy_section(bytes, find(info, kRestFrames), vertex_count, a.rest_frames)).empty() ||
      !(e = copy_section(bytes, find(info, kRestEdges), vertex_count, a.rest_edge_local)).empty() ||
      !(e = copy_section(bytes, find(info, kGuideGroups), guides, a.guide_group)).empty() ||
      !(e = copy_section(bytes, find(info, kFollowOffsets), follow_count, a.follow_offsets)).empty())
    return fail(e, info);
  if (const SectionInfo* uv = find(info, kRootUv)) {
    if (!(e = copy_section(bytes, uv, guides, a.root_uv)).empty()) return fail(e, info);
  }
  if (const SectionInfo* b = find(info, kBoneWeights)) {
    if (b->stride != kBoneRecordSize || b->count != guides)
      return fail("section BONE: expected " + std::to_string(guides) + " records of " +
                      std::to_string(kBoneRecordSize) + " bytes",
                  info);
    a.bone_weights.resize(guides);
    for (uint64_t i = 0; i < guides; ++i) {
      for (size_t k = 0; k < kMaxBoneInfluences; ++k) {
        a.bone_weights[i].bone[k] = load<uint32_t>(bytes, b->offset + i * kBoneRecordSize + 4 * k);
        a.bone_weights[i].weight[k] = load<float>(bytes, b->offset + i * kBoneRecordSize + 16 + 4 * k);
      }
    }
  }
  const auto problems = validate(a);
  if (!problems.empty()) return fail("inconsistent asset: " + problems.front(), info);
  r.asset = std::move(a);
  return r;
}

}  // namespace

static ReadResult inspect_impl(std::span<const std::byte> bytes) {
  if (bytes.empty()) return fail("empty file");
  if (bytes.size() < kHeaderSize || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) {
    if (bytes.size() >= 4 && std::memcmp(bytes.data() + 1, "TVK", 3) == 0)
      return fail("header: signature damaged (line endings converted or 8th bit stripped in transfer?)");
    return fail("header: not a .tvkhair file (signature missing)");
  }
  FileInfo info;
  info.major = load<uint16_t>(bytes, kOffMajor);
  info.minor = load<uint16_t>(bytes, kOffMinor);
  info.file_size = load<uint64_t>(bytes, kOffFileSize);
  if (info.major > kFormatMajor)
    return fail("header: format version " + std::to_string(info.major) + "." + std::to_string(info.minor) +
                    " is newer than this reader (" + std::to_string(kFormatMajor) + "." +
                    std::to_string(kFormatMinor) + "); update TressVK or re-bake with this version",
                info);
  if (info.major < kFormatMajor)
    return fail("header: format version " + std::to_string(info.major) + "." + std::to_string(info.minor) +
                    " is older than any this reader knows; re-bake the asset",
                info);
  std::array<std::byte, kHeaderSize> header{};
  std::memcpy(header.data(), bytes.data(), kHeaderSize);
  const uint32_t header_crc = load<uint32_t>(bytes, kOffHeaderCrc);
  store(std::span<std::byte>(header), kOffHeaderCrc, uint32_t{0});
  if (crc32(header) != header_crc) return fail("header: checksum mismatch (the header is damaged)", info);
  const uint32_t header_size = load<uint32_t>(bytes, kOffHeaderSize);
  if (header_size < kHeaderSize) return fail("header: header_size " + std::to_string(header_size) + " < 64", info);
  if (info.file_size != bytes.size())
    return fail("header: file_size says " + std::to_string(info.file_size) + " bytes but the file has " +
                    std::to_string(bytes.size()) + " (truncated or appended to)",
                info);
  const uint32_t section_count = load<uint32_t>(bytes, kOffSectionCount);
  const uint64_t table_offset = load<uint64_t>(bytes, kOffTableOffset);
  const uint32_t entry_size = load<uint32_t>(bytes, kOffEntrySize);
  if (entry_size < kTableEntrySize)
    return fail("header: section table entry size " + std::to_string(entry_size) + " < 48", info);
  if (table_offset < header_size || table_offset > bytes.size() ||
      section_count > (bytes.size() - table_offset) / entry_size)
    return fail("header: section table (" + std::to_string(section_count) + " entries at offset " +
                    std::to_string(table_offset) + ") lies outside the file",
                info);
  const uint64_t table_end = table_offset + uint64_t{section_count} * entry_size;
  if (crc32(bytes.subspan(table_offset, table_end - table_offset)) != load<uint32_t>(bytes, kOffTableCrc))
    return fail("section table: checksum mismatch (the table is damaged)", info);

  info.checksums_ok = true;
  for (uint32_t i = 0; i < section_count; ++i) {
    const size_t e = static_cast<size_t>(table_offset + uint64_t{i} * entry_size);
    SectionInfo s;
    s.id = load<uint32_t>(bytes, e + kEntId);
    s.name = fourcc_name(s.id);
    s.offset = load<uint64_t>(bytes, e + kEntOffset);
    s.size = load<uint64_t>(bytes, e + kEntSize);
    s.stride = load<uint32_t>(bytes, e + kEntStride);
    s.count = load<uint64_t>(bytes, e + kEntCount);
    s.stored_crc = load<uint32_t>(bytes, e + kEntCrc);
    const std::string where = "section table entry " + std::to_string(i) + " (" + s.name + "): ";
    if (s.offset < table_end || s.offset > bytes.size() || s.size > bytes.size() - s.offset)
      return fail(where + "offset " + std::to_string(s.offset) + " size " + std::to_string(s.size) +
                      " lies outside the data area",
                  info);
    if (s.offset % kAlignment != 0) return fail(where + "offset not aligned to 64 bytes", info);
    // Division, not multiplication: count x stride could wrap around for damaged values.
    if (s.stride == 0 || s.size % s.stride != 0 || s.count != s.size / s.stride)
      return fail(where + "size " + std::to_string(s.size) + " is not count " + std::to_string(s.count) +
                      " x stride " + std::to_string(s.stride),
                  info);
    if (find(info, s.id)) return fail(where + "duplicate section", info);
    s.actual_crc = crc32(bytes.subspan(static_cast<size_t>(s.offset), static_cast<size_t>(s.size)));
    s.crc_ok = s.actual_crc == s.stored_crc;
    info.checksums_ok = info.checksums_ok && s.crc_ok;
    info.sections.push_back(s);
  }
  // Sections must not overlap, and every byte outside header, table and sections must be zero padding: then a
  // flipped byte anywhere in the file is detected.
  std::vector<std::pair<uint64_t, uint64_t>> spans{{0, header_size}, {table_offset, table_end}};
  for (const auto& s : info.sections) spans.emplace_back(s.offset, s.offset + s.size);
  std::sort(spans.begin(), spans.end());
  uint64_t covered = 0;
  for (size_t i = 0; i < spans.size(); ++i) {
    if (spans[i].first < covered) return fail("section table: sections overlap each other or the table", info);
    const uint64_t gap_end = spans[i].first;
    for (uint64_t b = covered; b < gap_end; ++b)
      if (bytes[b] != std::byte{0}) {
        info.checksums_ok = false;
        return fail("padding byte at offset " + std::to_string(b) + " is not zero (the file is damaged)", info);
      }
    covered = std::max(covered, spans[i].second);
  }
  for (uint64_t b = covered; b < bytes.size(); ++b)
    if (bytes[b] != std::byte{0}) {
      info.checksums_ok = false;
      return fail("padding byte at offset " + std::to_string(b) + " is not zero (the file is damaged)", info);
    }
  ReadResult r;
  r.status = ReadStatus::kOk;
  r.info = std::move(info);
  return r;
}

ReadResult inspect(std::span<const std::byte> bytes) {
  try {
    return inspect_impl(bytes);
  } catch (const std::exception& ex) {  // only allocation failure is possible here; still never throw
    return fail(std::string("cannot inspect the asset: ") + ex.what());
  }
}

ReadResult read(std::span<const std::byte> bytes) {
  try {
    return read_impl(bytes);
  } catch (const std::bad_alloc&) {
    return fail("out of memory while reading the asset");
  } catch (const std::exception& ex) {
    return fail(std::string("unexpected error while reading: ") + ex.what());
  }
}

ReadResult read_file(const std::filesystem::path& path) {
  ReadResult r;
  try {
    std::ifstream f(path, std::ios::binary | std::ios::ate);
    if (!f) {
      r.status = ReadStatus::kIoError;
      r.error = path.string() + ": cannot open";
      return r;
    }
    const auto size = static_cast<std::streamsize>(f.tellg());
    std::vector<std::byte> bytes(static_cast<size_t>(std::max<std::streamsize>(size, 0)));
    f.seekg(0);
    if (size > 0 && !f.read(reinterpret_cast<char*>(bytes.data()), size)) {
      r.status = ReadStatus::kIoError;
      r.error = path.string() + ": read error";
      return r;
    }
    r = read(bytes);
    if (!r.ok()) r.error = path.string() + ": " + r.error;
  } catch (const std::exception& ex) {
    r.status = ReadStatus::kIoError;
    r.error = path.string() + ": " + ex.what();
  }
  return r;
}

}  // namespace tressvk::asset
