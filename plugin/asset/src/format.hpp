// Byte layout of .tvkhair files, shared by the reader and the writer (specification: docs/asset-format.md).
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

namespace tressvk::asset::format {

static_assert(std::endian::native == std::endian::little,
              "the .tvkhair reader and writer copy little-endian values directly; add byte swapping for this host");

// PNG-style signature: a high-bit byte catches 7-bit transfers, CR LF catches line-ending conversion, 0x1A stops
// DOS `type`, the final LF catches LF -> CR LF.
inline constexpr unsigned char kMagic[8] = {0x89, 'T', 'V', 'K', '\r', '\n', 0x1A, '\n'};
inline constexpr uint32_t kHeaderSize = 64;
inline constexpr uint32_t kTableEntrySize = 48;
inline constexpr uint64_t kAlignment = 64;

// Header field offsets.
inline constexpr size_t kOffMajor = 8, kOffMinor = 10, kOffHeaderSize = 12, kOffFileSize = 16,
                        kOffSectionCount = 24, kOffFlags = 28, kOffTableOffset = 32, kOffEntrySize = 40,
                        kOffTableCrc = 44, kOffHeaderCrc = 48;
// Table entry field offsets.
inline constexpr size_t kEntId = 0, kEntFlags = 4, kEntOffset = 8, kEntSize = 16, kEntStride = 24, kEntCount = 32,
                        kEntCrc = 40;

constexpr uint32_t fourcc(const char (&s)[5]) {
  return static_cast<uint32_t>(static_cast<unsigned char>(s[0])) |
         static_cast<uint32_t>(static_cast<unsigned char>(s[1])) << 8 |
         static_cast<uint32_t>(static_cast<unsigned char>(s[2])) << 16 |
         static_cast<uint32_t>(static_cast<unsigned char>(s[3])) << 24;
}

inline constexpr uint32_t kMeta = fourcc("META");  // counts, origin, names, bake settings (binary, stride 1)
inline constexpr uint32_t kRestPositions = fourcc("RPOS");
inline constexpr uint32_t kRestLengths = fourcc("RLEN");
inline constexpr uint32_t kRestFrames = fourcc("RFRM");
inline constexpr uint32_t kRestEdges = fourcc("REDG");
inline constexpr uint32_t kGuideGroups = fourcc("GGRP");
inline constexpr uint32_t kRootUv = fourcc("RUVS");       // optional
inline constexpr uint32_t kBoneWeights = fourcc("BONE");  // optional
inline constexpr uint32_t kFollowOffsets = fourcc("FOFS");

inline constexpr uint32_t kBoneRecordSize = 32;  // u32 bone[4], f32 weight[4]

inline std::string fourcc_name(uint32_t id) {
  std::string s(4, ' ');
  for (int i = 0; i < 4; ++i) {
    const auto c = static_cast<char>((id >> (8 * i)) & 0xFFu);
    s[static_cast<size_t>(i)] = (c >= 0x20 && c < 0x7F) ? c : '?';
  }
  return s;
}

template <typename T>
T load(std::span<const std::byte> bytes, size_t offset) {
  T v{};
  std::memcpy(&v, bytes.data() + offset, sizeof(T));
  return v;
}

template <typename T>
void store(std::span<std::byte> bytes, size_t offset, T v) {
  std::memcpy(bytes.data() + offset, &v, sizeof(T));
}

constexpr uint64_t align_up(uint64_t v) { return (v + kAlignment - 1) / kAlignment * kAlignment; }

}  // namespace tressvk::asset::format
