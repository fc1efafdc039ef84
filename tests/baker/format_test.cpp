// The .tvkhair format: round trip, damage detection in every part of the file, version rules. Runs under
// ASan/UBSan too (label "sanitize").
#include "test_support.hpp"

#include <tressvk/baker/procedural.hpp>

#include <catch2/matchers/catch_matchers_string.hpp>

#include <cstring>

using namespace tressvk;
using Catch::Matchers::ContainsSubstring;

namespace {

asset::HairAsset small_asset(bool extras) {
  baker::BuiltinGroomOptions o;
  o.guide_count = 40;
  o.follow_per_guide = 2;
  o.vertices_per_strand = 6;
  auto a = baker::make_builtin_groom("curly", o);
  if (extras) {  // optional sections too
    a.root_uv.assign(a.guide_count(), {0.25f, 0.75f});
    a.bone_names = {"head", "neck"};
    a.bone_weights.assign(a.guide_count(), asset::BoneInfluences{{0, 1, 0, 0}, {0.75f, 0.25f, 0.0f, 0.0f}});
    a.groups.push_back({"unused"});
  }
  return a;
}

// Sets a header field and re-seals the header checksum, as a writer of another version would.
void patch_header_u16(std::vector<std::byte>& b, size_t offset, uint16_t value) {
  std::memcpy(b.data() + offset, &value, 2);
  const uint32_t zero = 0;
  std::memcpy(b.data() + 48, &zero, 4);
  const uint32_t crc = asset::crc32(std::span<const std::byte>(b.data(), 64));
  std::memcpy(b.data() + 48, &crc, 4);
}

}  // namespace

TEST_CASE("CRC-32 matches the IEEE check value", "[baker][format]") {
  const char* s = "123456789";
  CHECK(asset::crc32(std::as_bytes(std::span(s, 9))) == 0xCBF43926u);
  CHECK(asset::crc32({}) == 0u);
}

TEST_CASE("Format: write -> read gives the same asset, and the same bytes again", "[baker][format]") {
  for (bool extras : {false, true}) {
    const auto a = small_asset(extras);
    const auto bytes = asset::write(a);
    const auto r = asset::read(bytes);
    REQUIRE(r.ok());
    CHECK(r.asset.rest_positions == a.rest_positions);
    CHECK(r.asset.rest_lengths == a.rest_lengths);
    CHECK(r.asset.rest_frames == a.rest_frames);
    CHECK(r.asset.rest_edge_local == a.rest_edge_local);
    CHECK(r.asset.follow_offsets == a.follow_offsets);
    CHECK(r.asset.guide_group == a.guide_group);
    CHECK(r.asset.root_uv == a.root_uv);
    CHECK(r.asset.bone_names == a.bone_names);
    CHECK(r.asset.bone_weights.size() == a.bone_weights.size());
    CHECK(r.asset.origin == a.origin);
    CHECK(r.asset.bake_settings == a.bake_settings);
    CHECK(asset::write(r.asset) == bytes);
    CHECK(bytes.size() % 64 == 0);
    for (const auto& s : r.info.sections) CHECK(s.offset % 64 == 0);
  }
}

TEST_CASE("Format: a flipped byte anywhere is detected (header, table, every section, padding)", "[baker][format]") {
  const auto bytes = asset::write(small_asset(true));
  const auto info = asset::inspect(bytes).info;
  REQUIRE(info.sections.size() == 9);
  std::vector<size_t> where;
  for (size_t i = 0; i < 64 + info.sections.size() * 48; ++i) where.push_back(i);  // every header and table byte
  for (const auto& s : info.sections) {
    for (uint64_t k = 0; k < s.size; k += std::max<uint64_t>(1, s.size / 37)) where.push_back(static_cast<size_t>(s.offset + k));
    if (s.size) where.push_back(static_cast<size_t>(s.offset + s.size - 1));
    if (s.offset + s.size < bytes.size() && (s.offset + s.size) % 64 != 0) where.push_back(static_cast<size_t>(s.offset + s.size));
  }
  where.push_back(bytes.size() - 1);
  for (size_t at : where) {
    for (std::byte mask : {std::byte{0x01}, std::byte{0x80}}) {
      auto b = bytes;
      b[at] ^= mask;
      const auto r = asset::read(b);
      INFO("byte " << at);
      CHECK_FALSE(r.ok());
      CHECK_FALSE(r.error.empty());
    }
  }
}

TEST_CASE("Format: truncation, appended bytes and text-mode mangling are refused", "[baker][format]") {
  const auto bytes = asset::write(small_asset(false));
  for (size_t n : {size_t{0}, size_t{7}, size_t{63}, size_t{64}, bytes.size() / 2, bytes.size() - 1}) {
    const auto r = asset::read(std::span(bytes.data(), n));
    CHECK_FALSE(r.ok());
  }
  auto longer = bytes;
  longer.push_back(std::byte{0});
  CHECK_THAT(asset::read(longer).error, ContainsSubstring("file_size"));
  // LF -> CRLF conversion of the signature.
  auto mangled = bytes;
  mangled.insert(mangled.begin() + 5, std::byte{'\r'});
  CHECK_THAT(asset::read(mangled).error, ContainsSubstring("signature"));
}

TEST_CASE("Format: newer major versions refused with a clear message; other minor versions accepted", "[baker][format]") {
  const auto bytes = asset::write(small_asset(false));
  auto newer = bytes;
  patch_header_u16(newer, 8, 2);
  const auto r = asset::read(newer);
  CHECK_FALSE(r.ok());
  CHECK_THAT(r.error, ContainsSubstring("newer") && ContainsSubstring("2.0"));
  auto older_major = bytes;
  patch_header_u16(older_major, 8, 0);
  CHECK_FALSE(asset::read(older_major).ok());
  // Minor versions only add things a reader may ignore (extra sections, trailing META fields): accepted.
  for (uint16_t minor : {uint16_t{0}, uint16_t{3}}) {
    auto m = bytes;
    patch_header_u16(m, 10, minor);
    const auto rm = asset::read(m);
    CHECK(rm.ok());
    CHECK(rm.info.minor == minor);
  }
}

TEST_CASE("Format: inconsistent contents are refused even with good checksums", "[baker][format]") {
  auto a = small_asset(false);
  a.rest_lengths[3] *= 1.5f;
  CHECK_FALSE(asset::validate(a).empty());
  const auto r = asset::read(asset::write(a));
  CHECK_FALSE(r.ok());
  CHECK_THAT(r.error, ContainsSubstring("rest length"));
  auto b = small_asset(false);
  b.guide_group[0] = 7;
  CHECK_THAT(asset::read(asset::write(b)).error, ContainsSubstring("group"));
  auto c = small_asset(false);
  c.rest_frames[2] = {0.0f, 0.0f, 0.0f, 2.0f};
  CHECK_THAT(asset::read(asset::write(c)).error, ContainsSubstring("quaternion"));
}

TEST_CASE("Format: streamed write_file gives the same bytes as write", "[baker][format]") {
  const auto a = small_asset(true);
  const auto path = tvk_test::temp_dir() / "streamed.tvkhair";
  asset::FileInfo info;
  REQUIRE(asset::write_file(path, a, &info).empty());
  const auto bytes = asset::write(a);
  CHECK(tvk_test::read_bytes(path) == bytes);
  CHECK(info.file_size == bytes.size());
  CHECK(info.sections.size() == asset::inspect(bytes).info.sections.size());
  CHECK_FALSE(asset::write_file(tvk_test::temp_dir() / "no_dir" / "x.tvkhair", a).empty());
}

TEST_CASE("Format: read_file reports I/O errors separately", "[baker][format]") {
  const auto r = asset::read_file(tvk_test::temp_dir() / "does_not_exist.tvkhair");
  CHECK(r.status == asset::ReadStatus::kIoError);
  CHECK_THAT(r.error, ContainsSubstring("does_not_exist"));
}
