// docs/asset-format.md, checked byte by byte with an independent reader written from the document alone.
#include "test_support.hpp"

#include <cstring>
#include <map>

using namespace tressvk;

namespace {

template <typename T>
T at(const std::vector<std::byte>& b, size_t offset) {
  T v{};
  REQUIRE(offset + sizeof(T) <= b.size());
  std::memcpy(&v, b.data() + offset, sizeof(T));
  return v;
}

// A hand-made asset: 2 guides x 4 vertices, straight along +X, 1 follow each, bones and UVs.
asset::HairAsset hand_made() {
  asset::HairAsset a;
  a.vertices_per_strand = 4;
  a.follow_per_guide = 1;
  a.tip_separation = 0.25f;
  a.origin = {1.0, 2.0, 3.0};
  for (int g = 0; g < 2; ++g)
    for (int v = 0; v < 4; ++v) {
      a.rest_positions.push_back({0.01f * static_cast<float>(v), 0.0f, 0.005f * static_cast<float>(g), v < 2 ? 0.0f : 1.0f});
      a.rest_lengths.push_back(v < 3 ? 0.01f : 0.0f);
      a.rest_frames.push_back({0.0f, 0.0f, 0.0f, 1.0f});
      a.rest_edge_local.push_back({v < 3 ? 0.01f : 0.0f, 0.0f, 0.0f, 0.0f});
    }
  a.guide_group = {0, 1};
  a.root_uv = {{0.5f, 0.25f}, {0.75f, 1.0f}};
  a.bone_names = {"head"};
  a.bone_weights = {asset::BoneInfluences{{0, 0, 0, 0}, {1, 0, 0, 0}}, asset::BoneInfluences{{0, 0, 0, 0}, {1, 0, 0, 0}}};
  a.follow_offsets = {{0.0f, 0.001f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.001f, 0.0f}};
  a.groups = {{"left"}, {"right"}};
  a.bake_settings = "{}";
  return a;
}

}  // namespace

TEST_CASE("Spec: header, table, sections and META exactly as documented", "[baker][format]") {
  const auto a = hand_made();
  REQUIRE(asset::validate(a).empty());
  const auto b = asset::write(a);

  const unsigned char magic[8] = {0x89, 'T', 'V', 'K', 0x0D, 0x0A, 0x1A, 0x0A};
  CHECK(std::memcmp(b.data(), magic, 8) == 0);
  CHECK(at<uint16_t>(b, 8) == 1);
  CHECK(at<uint16_t>(b, 10) == 0);
  CHECK(at<uint32_t>(b, 12) == 64);
  CHECK(at<uint64_t>(b, 16) == b.size());
  const auto count = at<uint32_t>(b, 24);
  CHECK(at<uint32_t>(b, 28) == 0);
  CHECK(at<uint64_t>(b, 32) == 64);
  CHECK(at<uint32_t>(b, 40) == 48);
  CHECK(at<uint32_t>(b, 44) == asset::crc32(std::span(b).subspan(64, count * 48)));
  auto header = std::vector<std::byte>(b.begin(), b.begin() + 64);
  std::memset(header.data() + 48, 0, 4);
  CHECK(at<uint32_t>(b, 48) == asset::crc32(header));
  for (size_t i = 52; i < 64; ++i) CHECK(b[i] == std::byte{0});
  CHECK(b.size() % 64 == 0);

  struct Entry {
    uint64_t offset, size, count;
    uint32_t stride;
  };
  std::map<std::string, Entry> sections;
  std::vector<std::string> order;
  for (uint32_t i = 0; i < count; ++i) {
    const size_t e = 64 + 48 * i;
    std::string name(reinterpret_cast<const char*>(b.data() + e), 4);
    const Entry entry{at<uint64_t>(b, e + 8), at<uint64_t>(b, e + 16), at<uint64_t>(b, e + 32), at<uint32_t>(b, e + 24)};
    CHECK(at<uint32_t>(b, e + 4) == 0);
    CHECK(at<uint32_t>(b, e + 28) == 0);
    CHECK(at<uint32_t>(b, e + 44) == 0);
    CHECK(entry.offset % 64 == 0);
    CHECK(entry.size == entry.count * entry.stride);
    CHECK(at<uint32_t>(b, e + 40) == asset::crc32(std::span(b).subspan(entry.offset, entry.size)));
    sections[name] = entry;
    order.push_back(name);
  }
  CHECK(order == std::vector<std::string>{"META", "RPOS", "RLEN", "RFRM", "REDG", "GGRP", "RUVS", "BONE", "FOFS"});
  CHECK(sections["RPOS"].stride == 16);
  CHECK(sections["RPOS"].count == 8);
  CHECK(sections["RLEN"].stride == 4);
  CHECK(sections["RFRM"].stride == 16);
  CHECK(sections["REDG"].stride == 16);
  CHECK(sections["GGRP"].stride == 2);
  CHECK(sections["GGRP"].count == 2);
  CHECK(sections["RUVS"].stride == 8);
  CHECK(sections["BONE"].stride == 32);
  CHECK(sections["FOFS"].stride == 16);
  CHECK(sections["FOFS"].count == 2);
  CHECK(at<float>(b, sections["RPOS"].offset + 16 * 5 + 8) == 0.005f);  // guide 1, vertex 1, z
  CHECK(at<float>(b, sections["RPOS"].offset + 16 * 2 + 12) == 1.0f);   // inverse mass of vertex 2
  CHECK(at<uint16_t>(b, sections["GGRP"].offset + 2) == 1);
  CHECK(at<float>(b, sections["RUVS"].offset + 8) == 0.75f);
  CHECK(at<float>(b, sections["BONE"].offset + 16) == 1.0f);             // weight[0] after bone[4]
  CHECK(at<float>(b, sections["FOFS"].offset + 16 + 8) == 0.001f);

  // META: N, K, G, tip separation, origin, groups, bones, bake settings.
  size_t m = sections["META"].offset;
  CHECK(at<uint32_t>(b, m) == 4);
  CHECK(at<uint32_t>(b, m + 4) == 1);
  CHECK(at<uint32_t>(b, m + 8) == 2);
  CHECK(at<float>(b, m + 12) == 0.25f);
  CHECK(at<double>(b, m + 16) == 1.0);
  CHECK(at<double>(b, m + 32) == 3.0);
  m += 40;
  auto read_string = [&] {
    const auto n = at<uint32_t>(b, m);
    std::string s(reinterpret_cast<const char*>(b.data() + m + 4), n);
    m += 4 + n;
    return s;
  };
  CHECK(at<uint32_t>(b, m) == 2);
  m += 4;
  CHECK(read_string() == "left");
  CHECK(read_string() == "right");
  CHECK(at<uint32_t>(b, m) == 1);
  m += 4;
  CHECK(read_string() == "head");
  CHECK(read_string() == "{}");
  CHECK(m == sections["META"].offset + sections["META"].size);
}

TEST_CASE("Spec: unknown sections from a later minor version are ignored", "[baker][format]") {
  // Build a 1.1-style file by hand: this writer's sections plus an extra "XTRA" section, table and CRCs redone.
  const auto a = hand_made();
  const auto b = asset::write(a);
  const auto count = at<uint32_t>(b, 24);
  std::vector<std::byte> out(64 + (count + 1) * 48, std::byte{0});
  std::memcpy(out.data(), b.data(), 64);
  const uint64_t shift = 64 * ((64 + (count + 1) * 48 + 63) / 64) - 64 * ((64 + count * 48 + 63) / 64);
  for (uint32_t i = 0; i < count; ++i) {
    std::memcpy(out.data() + 64 + 48 * i, b.data() + 64 + 48 * i, 48);
    const uint64_t off = at<uint64_t>(b, 64 + 48 * i + 8) + shift;
    std::memcpy(out.data() + 64 + 48 * i + 8, &off, 8);
  }
  const uint64_t body_start = 64 * ((64 + count * 48 + 63) / 64);
  out.resize(body_start + shift);
  out.insert(out.end(), b.begin() + static_cast<std::ptrdiff_t>(body_start), b.end());
  const uint64_t extra_offset = out.size();
  const char extra[64] = "future data";
  out.insert(out.end(), reinterpret_cast<const std::byte*>(extra), reinterpret_cast<const std::byte*>(extra) + 64);
  const size_t e = 64 + 48 * count;
  const uint32_t id = 'X' | 'T' << 8 | 'R' << 16 | 'A' << 24;
  const uint64_t size = 64, n = 64;
  const uint32_t stride = 1, crc = asset::crc32(std::span(out).subspan(extra_offset, 64));
  std::memcpy(out.data() + e, &id, 4);
  std::memcpy(out.data() + e + 8, &extra_offset, 8);
  std::memcpy(out.data() + e + 16, &size, 8);
  std::memcpy(out.data() + e + 24, &stride, 4);
  std::memcpy(out.data() + e + 32, &n, 8);
  std::memcpy(out.data() + e + 40, &crc, 4);
  const uint16_t minor = 1;
  const uint32_t new_count = count + 1;
  const uint64_t file_size = out.size();
  std::memcpy(out.data() + 10, &minor, 2);
  std::memcpy(out.data() + 16, &file_size, 8);
  std::memcpy(out.data() + 24, &new_count, 4);
  const uint32_t table_crc = asset::crc32(std::span(out).subspan(64, new_count * 48));
  std::memcpy(out.data() + 44, &table_crc, 4);
  std::memset(out.data() + 48, 0, 4);
  const uint32_t header_crc = asset::crc32(std::span(out).subspan(0, 64));
  std::memcpy(out.data() + 48, &header_crc, 4);

  const auto r = asset::read(out);
  INFO(r.error);
  REQUIRE(r.ok());
  CHECK(r.info.minor == 1);
  CHECK(r.info.sections.size() == count + 1);
  CHECK(r.asset.rest_positions == a.rest_positions);
  CHECK(r.asset.groups.size() == 2);
}
