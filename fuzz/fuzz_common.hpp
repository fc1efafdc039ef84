// Shared by the fuzz targets: what counts as a finding. A target returns normally for every input the code
// accepts or refuses with its documented error (tressvk::baker::InputError, asset::ReadStatus::kInvalid, a
// TvkResult); anything else -- a crash, a sanitizer report, another exception, an accepted input whose output
// fails validation -- ends the process through finding(), which libFuzzer records as a crash with its input.
#pragma once

#include <tressvk/asset.hpp>
#include <tressvk/asset_io.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <span>
#include <string>
#include <vector>

namespace tressvk::fuzz {

[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "FUZZ FINDING: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

inline std::span<const std::byte> as_bytes(const uint8_t* data, size_t size) {
  return {reinterpret_cast<const std::byte*>(data), size};
}

// An asset a reader or the bake accepted must validate, and survive write -> read unchanged in shape.
inline void check_asset(const asset::HairAsset& a, const char* who) {
  const auto issues = asset::validate(a);
  if (!issues.empty()) finding(std::string(who) + " produced an asset that fails validation: " + issues.front());
  const auto bytes = asset::write(a);
  const auto again = asset::read(bytes);
  if (!again.ok()) finding(std::string(who) + ": write() then read() refused the asset: " + again.error);
  if (again.asset.guide_count() != a.guide_count() || again.asset.vertices_per_strand != a.vertices_per_strand)
    finding(std::string(who) + ": write() then read() changed the counts");
}

// A copy of a .tvkhair candidate with its file size and every checksum recomputed (layout:
// docs/asset-format.md), so that mutations get past the CRCs into the section parsers and validate(). Fields
// that do not fit the bytes are left alone for the reader to refuse.
inline std::vector<std::byte> with_fixed_checksums(const uint8_t* data, size_t size) {
  std::vector<std::byte> b(reinterpret_cast<const std::byte*>(data), reinterpret_cast<const std::byte*>(data) + size);
  if (size < 64) return b;
  auto get32 = [&](uint64_t at) { uint32_t v; std::memcpy(&v, b.data() + at, 4); return v; };
  auto get64 = [&](uint64_t at) { uint64_t v; std::memcpy(&v, b.data() + at, 8); return v; };
  auto put32 = [&](uint64_t at, uint32_t v) { std::memcpy(b.data() + at, &v, 4); };
  const uint64_t file_size = size;
  std::memcpy(b.data() + 16, &file_size, 8);
  const uint32_t count = get32(24), entry = get32(40);
  const uint64_t table = get64(32);
  if (entry >= 48 && table <= size && count <= (size - table) / entry) {
    for (uint32_t i = 0; i < count; ++i) {
      const uint64_t e = table + uint64_t{i} * entry;
      const uint64_t off = get64(e + 8), len = get64(e + 16);
      if (off <= size && len <= size - off)
        put32(e + 40, asset::crc32(std::span<const std::byte>(b).subspan(off, len)));
    }
    put32(44, asset::crc32(std::span<const std::byte>(b).subspan(table, uint64_t{count} * entry)));
  }
  put32(48, 0);
  put32(48, asset::crc32(std::span<const std::byte>(b).first(64)));
  return b;
}

}  // namespace tressvk::fuzz
