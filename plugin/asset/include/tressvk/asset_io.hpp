// Reading, writing and checking `.tvkhair` files (byte layout: docs/asset-format.md).
//
// Nothing here throws: every failure comes back as a result carrying a message that names the section and
// field at fault, so the plugin can pass it across its C interface unchanged.
#pragma once

#include <tressvk/asset.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace tressvk::asset {

inline constexpr uint16_t kFormatMajor = 1;
inline constexpr uint16_t kFormatMinor = 0;

// CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320, as zlib and PNG). `crc` continues a running value.
uint32_t crc32(std::span<const std::byte> bytes, uint32_t crc = 0);

// One entry of the section table, as found in a file.
struct SectionInfo {
  std::string name;           // the four-character id, e.g. "RPOS"
  uint32_t id = 0;            // the same id as a little-endian u32
  uint64_t offset = 0;        // from the start of the file
  uint64_t size = 0;          // bytes
  uint32_t stride = 0;        // bytes per element
  uint64_t count = 0;         // elements
  uint32_t stored_crc = 0;    // CRC-32 recorded in the table
  uint32_t actual_crc = 0;    // CRC-32 of the bytes found (0 when the section lies outside the file)
  bool crc_ok = false;
};

// The header and section table of a file, readable even when section contents are damaged (for `info`).
struct FileInfo {
  uint16_t major = 0;
  uint16_t minor = 0;
  uint64_t file_size = 0;
  std::vector<SectionInfo> sections;
  bool checksums_ok = false;  // header, table and every section
};

enum class ReadStatus {
  kOk,
  kIoError,       // the file could not be opened or read
  kInvalid,       // the bytes are not a valid .tvkhair file
};

struct ReadResult {
  ReadStatus status = ReadStatus::kInvalid;
  std::string error;  // empty when ok; otherwise names the section/field, e.g. "section RLEN: ..."
  HairAsset asset;
  FileInfo info;
  bool ok() const { return status == ReadStatus::kOk; }
};

// Parses the header and section table only (checksums computed). Fails on a bad header or table.
ReadResult inspect(std::span<const std::byte> bytes);
// Full read: header, table, checksums, then sections into a HairAsset, then validate().
ReadResult read(std::span<const std::byte> bytes);
ReadResult read_file(const std::filesystem::path& path);

// Serialises an asset. The bytes depend only on the asset (no time stamps, no paths). The asset should pass
// validate(); write() does not check it. `info_out`, when given, receives the header and section table written
// (as inspect() would report them, without a second checksum pass).
std::vector<std::byte> write(const HairAsset& asset, FileInfo* info_out = nullptr);

// Writes to a temporary file beside `path` and renames it into place, so a failure never leaves a partial file.
// Returns an empty string on success, otherwise an I/O error message naming the file.
std::string write_file(const std::filesystem::path& path, std::span<const std::byte> bytes);
// The same for an asset, streamed section by section (the same bytes as write(), without a copy in memory).
std::string write_file(const std::filesystem::path& path, const HairAsset& asset, FileInfo* info_out = nullptr);

// Checks that an in-memory asset is whole and self-consistent: counts, finite values, unit quaternions, rest
// lengths and rest edges that match the positions (to float32 precision relative to the segment length), group
// and bone indices in range, bone weights sorted and normalised. Returns the problems found (empty = valid).
std::vector<std::string> validate(const HairAsset& asset);

// Asset-space bounds (metres, origin added) over guide vertices, for reports.
struct Bounds {
  std::array<double, 3> min{};
  std::array<double, 3> max{};
};
Bounds guide_bounds(const HairAsset& asset);

}  // namespace tressvk::asset
