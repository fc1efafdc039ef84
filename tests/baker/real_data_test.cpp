// Every file in shared/data baked and checked: counts, roots, arc length, bones, groups, units.
#include "test_support.hpp"

#include <catch2/catch_approx.hpp>

#include <algorithm>
#include <map>

using namespace tressvk;
using Catch::Approx;

namespace {

struct Baked {
  baker::RawGroom raw;
  asset::HairAsset asset;
  baker::BakeReport report;
};

// The TressFX samples are authored in centimetres.
baker::BakeOptions centimetre_options(uint32_t vertices_per_strand) {
  baker::BakeOptions o;
  o.units_to_metres = 0.01;
  o.vertices_per_strand = vertices_per_strand;
  return o;
}

Baked bake_files(const std::vector<tvk_test::fs::path>& files, baker::BakeOptions o, const tvk_test::fs::path& bones = {}) {
  Baked b;
  for (const auto& f : files) {
    auto part = baker::import_file(f);
    if (!bones.empty()) baker::apply_tfxbone(part, bones);
    b.raw.append(part);
  }
  o.shuffle = false;  // guide k is then the k-th kept input strand
  b.asset = baker::bake(b.raw, o, &b.report);
  REQUIRE(asset::validate(b.asset).empty());
  // Through the file format and back: identical.
  const auto bytes = asset::write(b.asset);
  const auto r = asset::read(bytes);
  REQUIRE(r.ok());
  CHECK(r.asset.rest_positions == b.asset.rest_positions);
  return b;
}

double input_length(const baker::RawGroom& g, size_t s, double scale) {
  double l = 0;
  for (uint32_t i = g.strand_begin[s] + 1; i < g.strand_begin[s + 1]; ++i) {
    const auto& a = g.points[i - 1];
    const auto& b = g.points[i];
    l += std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
  }
  return l * scale;
}

// Roots of kept strands are the input roots; guide arc length never exceeds the input's and stays within the
// resampling loss the report states. `scale` is input units -> metres.
void check_roots_and_lengths(const Baked& b, double scale) {
  const auto& a = b.asset;
  size_t k = 0;
  double worst = 1.0;
  for (size_t s = 0; s < b.raw.strand_count() && k < a.guide_count(); ++s) {
    const auto& r = b.raw.points[b.raw.strand_begin[s]];
    const std::array<double, 3> root{r[0] * scale, r[1] * scale, r[2] * scale};
    const double tol = 1e-6 * (1 + std::sqrt(root[0] * root[0] + root[1] * root[1] + root[2] * root[2]));  // float32
    if (tvk_test::distance(tvk_test::position(a, static_cast<uint32_t>(k), 0), root) > tol)
      continue;  // a dropped strand (kept strands keep the input order with shuffle off)
    const double in = input_length(b.raw, s, scale);
    const double out = tvk_test::guide_length(a, static_cast<uint32_t>(k));
    // A polyline through points of the input polyline is never longer than it, up to the float32 rounding of
    // the stored positions: half an ulp (6e-8 relative) of their distance from the origin, per vertex.
    const auto& p = a.rest_positions[k * a.vertices_per_strand];
    const double magnitude = std::sqrt(double{p[0]} * p[0] + double{p[1]} * p[1] + double{p[2]} * p[2]) + in;
    CHECK(out <= in * (1 + 1e-9) + 2.0 * a.vertices_per_strand * 6e-8 * magnitude);
    worst = std::min(worst, out / in);
    ++k;
  }
  CHECK(k == a.guide_count());
  // Resampling cuts corners; on these grooms the loss stays below 10 % of any strand's length (kinked strands
  // such as the mohawk's, noted in AMD's issue #38, are the worst case).
  CHECK(worst > 0.9);
}

}  // namespace

TEST_CASE("Real data: Unity Cube_Hair.obj (Blender 2-index edges)", "[baker][data]") {
  TVK_REQUIRE_DATA(dir);
  const auto b = bake_files({dir / "unity" / "Cube_Hair.obj"}, {});
  CHECK(b.raw.strand_count() == 1000);
  CHECK(b.report.input_vertices == 5000);
  CHECK(b.asset.guide_count() == 1000);
  check_roots_and_lengths(b, 1.0);
  for (uint32_t g = 0; g < 1000; ++g) {
    const auto r = tvk_test::position(b.asset, g, 0);
    CHECK(std::max({std::abs(r[0]), std::abs(r[1]), std::abs(r[2])}) == Approx(1.0));  // roots on the cube's surface
    CHECK(tvk_test::guide_length(b.asset, g) == Approx(4.0).epsilon(1e-6));
  }
}

TEST_CASE("Real data: Ratboy mohawk .tfx v4 with .tfxbone 4.x", "[baker][data]") {
  TVK_REQUIRE_DATA(dir);
  const auto r = dir / "tressfx" / "ratboy";
  baker::BakeOptions o;
  o.follow_per_guide = 2;
  const auto b = bake_files({r / "Ratboy_mohawk.tfx"}, o, r / "Ratboy_mohawk.tfxbone");
  CHECK(b.raw.strand_count() == 2228);
  // 9 strands are shorter than 1 mm; those below 1 % of the median length (0.8 mm) are dropped and counted.
  CHECK(b.report.dropped_short >= 1);
  CHECK(b.report.dropped_short <= 9);
  CHECK(b.asset.guide_count() + b.report.dropped_short == 2228);
  CHECK(b.report.merged_vertices > 0);  // the 31 sub-micrometre segments
  CHECK(b.asset.bone_names.size() == 105);
  CHECK(b.asset.bone_weights.size() == b.asset.guide_count());
  CHECK(b.asset.root_uv.size() == b.asset.guide_count());
  CHECK(b.asset.follow_offsets.size() == 2 * b.asset.guide_count());
  check_roots_and_lengths(b, 1.0);
}

TEST_CASE("Real data: TressFX 3 ponytail, four sections in cm, merged into four groups", "[baker][data]") {
  TVK_REQUIRE_DATA(dir);
  const auto p = dir / "tressfx" / "ponytail";
  const baker::BakeOptions o = centimetre_options(16);
  const auto b = bake_files({p / "front_top.tfx", p / "side.tfx", p / "back.tfx", p / "tail.tfx"}, o);
  REQUIRE(b.asset.groups.size() == 4);
  std::map<std::string, int> counts;
  for (uint16_t g : b.asset.guide_group) counts[b.asset.groups[g].name]++;
  CHECK(counts["front_top"] + counts["side"] + counts["back"] + counts["tail"] + static_cast<int>(b.report.dropped_short) ==
        876 + 3066 + 517 + 474);
  CHECK(counts["back"] > 500);
  check_roots_and_lengths(b, 0.01);
  // back.tfx has both ends immovable: its strands keep pinned tips.
  const uint32_t n = b.asset.vertices_per_strand;
  for (uint32_t g = 0; g < b.asset.guide_count(); ++g) {
    const bool back = b.asset.groups[b.asset.guide_group[g]].name == "back";
    CHECK((b.asset.rest_positions[g * n + n - 1][3] == 0.0f) == back);
  }
  // Mean length of the tail section is about 65.6 cm (tressfx-reference.md §11).
  double sum = 0;
  for (uint32_t g = 0; g < b.asset.guide_count(); ++g)
    if (b.asset.groups[b.asset.guide_group[g]].name == "tail") sum += tvk_test::guide_length(b.asset, g);
  CHECK(sum / counts["tail"] == Approx(0.656).epsilon(0.03));
}

TEST_CASE("Real data: bear fur, 48,113 short strands with near-zero segments", "[baker][data]") {
  TVK_REQUIRE_DATA(dir);
  const baker::BakeOptions o = centimetre_options(4);
  const auto b = bake_files({dir / "tressfx" / "bear" / "bear.tfx"}, o);
  CHECK(b.raw.strand_count() == 48113);
  CHECK(b.asset.guide_count() + b.report.dropped_short == 48113);
  CHECK(b.report.dropped_short < 48113 / 100);  // only the degenerate few
  check_roots_and_lengths(b, 0.01);
}

TEST_CASE("Real data: TestHair1, straight strands from a sphere of radius 100", "[baker][data]") {
  TVK_REQUIRE_DATA(dir);
  const baker::BakeOptions o = centimetre_options(8);
  const auto b = bake_files({dir / "tressfx" / "testhair1" / "TestHair1.tfx"}, o);
  CHECK(b.asset.guide_count() + b.report.dropped_short == 10027);
  CHECK(b.report.max_relative_resample_error < 1e-3);  // straight strands resample almost exactly
  check_roots_and_lengths(b, 0.01);
}

TEST_CASE("Real data: Sintel hair (.tfx v4 without UVs) and its roots on the Sintel mesh", "[baker][data]") {
  TVK_REQUIRE_DATA(dir);
  const auto s = dir / "sintel";
  const auto b = bake_files({s / "sintel_hair.tfx"}, {});
  CHECK(b.asset.guide_count() == 228);
  CHECK(b.asset.root_uv.empty());  // offsetStrandUV = 0: no UVs, never header bytes read as UVs
  check_roots_and_lengths(b, 1.0);
  // Reverse every strand, then let the character mesh decide: the roots come back.
  auto raw = baker::import_tfx(s / "sintel_hair.tfx");
  auto flipped = raw;
  for (size_t i = 0; i < flipped.strand_count(); ++i)
    std::reverse(flipped.points.begin() + flipped.strand_begin[i], flipped.points.begin() + flipped.strand_begin[i + 1]);
  baker::orient_to_scalp(flipped, baker::load_scalp(s / "sintel.obj"));
  size_t restored = 0;
  for (size_t i = 0; i < raw.strand_count(); ++i) restored += flipped.points[flipped.strand_begin[i]] == raw.points[raw.strand_begin[i]];
  // sintel.obj is the whole character, not a scalp: a few strands end nearer the body (or touch it) than
  // their roots are to the head surface. Measured: 225 of 228 restored; demand at least 97 %.
  CHECK(restored >= raw.strand_count() * 97 / 100);
}
