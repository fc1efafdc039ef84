// TressFX .tfx v3/v4 and .tfxbone 4.x/5.x on hand-built bytes: layouts, bone reduction, and refusals.
#include "test_support.hpp"

#include <tressvk/baker/errors.hpp>

#include <catch2/catch_approx.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

#include <cstring>
#include <functional>
#include <limits>

using namespace tressvk;
using Catch::Approx;
using Catch::Matchers::ContainsSubstring;

namespace {

class Bytes {
 public:
  template <typename T>
  Bytes& put(T v) {
    const size_t at = b.size();
    b.resize(at + sizeof v);
    std::memcpy(b.data() + at, &v, sizeof v);
    return *this;
  }
  Bytes& pad_to(size_t n) {
    b.resize(n, std::byte{0});
    return *this;
  }
  template <typename T>
  void set(size_t at, T v) {
    std::memcpy(b.data() + at, &v, sizeof v);
  }
  std::vector<std::byte> b;
};

// Two strands of 4 vertices along +Y at x = 0 and x = 1 (cm-sized: 3 units long).
std::vector<std::byte> tfx_v4(bool with_uv) {
  Bytes t;
  t.put(4.0f).put(uint32_t{2}).put(uint32_t{4}).put(uint32_t{160}).put(with_uv ? uint32_t{160 + 2 * 4 * 16} : uint32_t{0});
  t.pad_to(160);
  for (int s = 0; s < 2; ++s)
    for (int v = 0; v < 4; ++v) t.put(static_cast<float>(s)).put(static_cast<float>(v)).put(0.0f).put(v < 2 ? 0.0f : 1.0f);
  if (with_uv) t.put(0.25f).put(0.5f).put(0.75f).put(1.0f);
  return t.b;
}

std::vector<std::byte> tfx_v3(int both_ends) {
  Bytes t;
  t.put(3.0f).put(uint32_t{2}).put(uint32_t{4}).put(uint32_t{0}).put(int32_t{both_ends});
  t.pad_to(144);
  t.put(uint32_t{296});
  t.pad_to(296);
  for (int s = 0; s < 2; ++s)
    for (int v = 0; v < 4; ++v) t.put(static_cast<float>(s)).put(static_cast<float>(v)).put(0.0f);
  return t.b;
}

Bytes bone_table(int bones) {
  Bytes t;
  t.put(int32_t{bones});
  for (int i = bones - 1; i >= 0; --i) {  // written out of order: names are placed by their index field
    t.put(int32_t{i}).put(int32_t{3}).put('b').put(static_cast<char>('0' + i)).put('\0');
  }
  return t;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const baker::InputError& e) {
    return e.what();
  }
  return "<no error>";
}

}  // namespace

TEST_CASE("TFX v4: positions, strand UVs, w ignored in favour of --pin", "[baker][tfx]") {
  auto g = baker::import_tfx_bytes(tfx_v4(true), "dir/hair.tfx");
  REQUIRE(g.strand_count() == 2);
  CHECK(g.group_names == std::vector<std::string>{"hair"});
  CHECK(g.points[5] == baker::Vec3{1, 1, 0});
  REQUIRE(g.strand_uv.size() == 2);
  CHECK(g.strand_uv[1] == std::array<float, 2>{0.75f, 1.0f});
  CHECK(baker::import_tfx_bytes(tfx_v4(false), "h.tfx").strand_uv.empty());  // offset 0: no UVs
  baker::BakeOptions o;
  o.pin = 1;
  o.shuffle = false;
  const auto a = baker::bake(g, o);
  CHECK(a.rest_positions[0][3] == 0.0f);
  CHECK(a.rest_positions[1][3] == 1.0f);
  CHECK(a.root_uv.size() == 2);
}

TEST_CASE("TFX v3: float3 positions; bothEndsImmovable pins the tips too", "[baker][tfx]") {
  baker::BakeOptions o;
  o.vertices_per_strand = 6;
  o.shuffle = false;
  const auto free_tips = baker::bake(baker::import_tfx_bytes(tfx_v3(0), "h.tfx"), o);
  const auto pinned_tips = baker::bake(baker::import_tfx_bytes(tfx_v3(1), "h.tfx"), o);
  CHECK(free_tips.rest_positions[5][3] == 1.0f);
  CHECK(pinned_tips.rest_positions[5][3] == 0.0f);
  CHECK(pinned_tips.rest_positions[4][3] == 0.0f);
  CHECK(pinned_tips.rest_positions[3][3] == 1.0f);
  CHECK(tvk_test::guide_length(free_tips, 1) == Approx(3.0));
}

TEST_CASE("tfxbone 4.x: fixed four influences, zero-weight slots ignored", "[baker][tfx]") {
  auto g = baker::import_tfx_bytes(tfx_v4(false), "h.tfx");
  Bytes t = bone_table(3);
  t.put(int32_t{2});
  for (int s = 0; s < 2; ++s) {
    t.put(int32_t{s}).put(int32_t{2}).put(0.25f).put(int32_t{s}).put(0.75f).put(int32_t{-1}).put(0.0f).put(int32_t{-1}).put(0.0f);
  }
  baker::apply_tfxbone_bytes(g, t.b, "h.tfxbone");
  CHECK(g.bone_names == std::vector<std::string>{"b0", "b1", "b2"});
  REQUIRE(g.strand_bones.size() == 2);
  CHECK(g.strand_bones[1].bone[0] == 1);
  CHECK(g.strand_bones[1].weight[0] == Approx(0.75f));
  CHECK(g.strand_bones[1].bone[1] == 2);
  CHECK(g.strand_bones[1].weight[2] == 0.0f);
  CHECK(g.bone_influences_dropped == 0);
}

TEST_CASE("tfxbone 5.x: counted influences; the 4 largest kept, renormalised, the rest counted", "[baker][tfx]") {
  auto g = baker::import_tfx_bytes(tfx_v4(false), "h.tfx");
  Bytes t = bone_table(6);
  t.put(int32_t{2});
  t.put(int32_t{1}).put(int32_t{1}).put(int32_t{5}).put(2.0f);  // strand 1 first: records may come in any order
  t.put(int32_t{0}).put(int32_t{6});
  const float w[6] = {0.05f, 0.3f, 0.1f, 0.2f, 0.25f, 0.1f};
  for (int k = 0; k < 6; ++k) t.put(int32_t{k}).put(w[k]);
  baker::apply_tfxbone_bytes(g, t.b, "h.tfxbone");
  const auto& b0 = g.strand_bones[0];
  // Kept: bones 1 (0.3), 4 (0.25), 3 (0.2), then 2 (0.1; ties with bone 5 go to the lower index).
  CHECK(b0.bone == std::array<uint32_t, 4>{1, 4, 3, 2});
  CHECK(b0.weight[0] == Approx(0.3f / 0.85f));
  CHECK(b0.weight[3] == Approx(0.1f / 0.85f));
  CHECK(b0.weight[0] + b0.weight[1] + b0.weight[2] + b0.weight[3] == Approx(1.0f));
  CHECK(g.bone_influences_dropped == 2);
  CHECK(g.strand_bones[1].bone[0] == 5);
  CHECK(g.strand_bones[1].weight[0] == 1.0f);
  baker::BakeOptions o;
  o.shuffle = false;
  const auto a = baker::bake(g, o);
  CHECK(asset::validate(a).empty());
  CHECK(a.bone_names.size() == 6);
}

TEST_CASE("TFX refusals name the file and the field", "[baker][tfx]") {
  CHECK_THAT(error_of([] { baker::import_tfx_bytes({}, "h.tfx"); }), ContainsSubstring("h.tfx") && ContainsSubstring("empty"));
  auto bad_version = tfx_v4(false);
  const float two = 2.0f;
  std::memcpy(bad_version.data(), &two, 4);
  CHECK_THAT(error_of([&] { baker::import_tfx_bytes(bad_version, "h.tfx"); }), ContainsSubstring("version"));
  auto truncated = tfx_v4(false);
  truncated.resize(truncated.size() - 1);
  CHECK_THAT(error_of([&] { baker::import_tfx_bytes(truncated, "h.tfx"); }), ContainsSubstring("past the end"));
  auto nan = tfx_v4(false);
  const float q = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(nan.data() + 160 + 5 * 16 + 4, &q, 4);
  CHECK_THAT(error_of([&] { baker::import_tfx_bytes(nan, "h.tfx"); }), ContainsSubstring("strand 1 vertex 1") && ContainsSubstring("non-finite"));
  auto zero = tfx_v4(false);
  std::memset(zero.data() + 4, 0, 4);
  CHECK_THAT(error_of([&] { baker::import_tfx_bytes(zero, "h.tfx"); }), ContainsSubstring("numHairStrands"));
  auto bad_uv = tfx_v4(false);
  const uint32_t far = 1u << 30;
  std::memcpy(bad_uv.data() + 16, &far, 4);
  CHECK_THAT(error_of([&] { baker::import_tfx_bytes(bad_uv, "h.tfx"); }), ContainsSubstring("offsetStrandUV"));
}

TEST_CASE("tfxbone refusals", "[baker][tfx]") {
  auto g = baker::import_tfx_bytes(tfx_v4(false), "h.tfx");
  {
    Bytes t = bone_table(2);
    t.put(int32_t{3});  // the hair has 2 strands
    CHECK_THAT(error_of([&] { baker::apply_tfxbone_bytes(g, t.b, "h.tfxbone"); }), ContainsSubstring("numStrands") && ContainsSubstring("h.tfxbone"));
  }
  {
    Bytes t = bone_table(2);
    t.put(int32_t{2});
    for (int s = 0; s < 2; ++s) t.put(int32_t{s}).put(int32_t{7}).put(1.0f).put(int32_t{0}).put(0.0f).put(int32_t{0}).put(0.0f).put(int32_t{0}).put(0.0f);
    CHECK_THAT(error_of([&] { baker::apply_tfxbone_bytes(g, t.b, "h.tfxbone"); }), ContainsSubstring("bone index 7"));
  }
  {
    Bytes t = bone_table(2);
    t.put(int32_t{2});
    t.put(int32_t{0}).put(int32_t{1}).put(int32_t{0}).put(1.0f);
    t.put(int32_t{0}).put(int32_t{1}).put(int32_t{1}).put(1.0f);  // strand 0 twice, strand 1 never
    CHECK_THAT(error_of([&] { baker::apply_tfxbone_bytes(g, t.b, "h.tfxbone"); }), ContainsSubstring("two records"));
  }
  {
    Bytes t = bone_table(2);
    t.put(int32_t{2});
    t.put(int32_t{0}).put(int32_t{1}).put(int32_t{0}).put(1.0f);
    CHECK_THAT(error_of([&] { baker::apply_tfxbone_bytes(g, t.b, "h.tfxbone"); }), ContainsSubstring("file ends"));
  }
  CHECK_THAT(error_of([&] { baker::apply_tfxbone_bytes(g, {}, "h.tfxbone"); }), ContainsSubstring("empty"));
}
