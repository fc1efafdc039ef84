// tressvk-bake end to end: exit codes, determinism, info/validate/export, atomic output, the CMake bake rule.
#include "test_support.hpp"

#include <nlohmann/json.hpp>

#include <catch2/catch_approx.hpp>

#include <fstream>
#include <sstream>

using namespace tressvk;
using tvk_test::quoted;
using tvk_test::run_bake;
namespace fs = std::filesystem;

namespace {

const std::string kSmallObj =
    "o crown\nv 0 0 0\nv 0 0.05 0.001\nv 0 0.1 0.004\nv 0 0.15 0.009\nl 1 2 3 4\n"
    "v 0.01 0 0\nv 0.01 0.05 -0.001\nv 0.01 0.1 -0.004\nv 0.012 0.15 -0.009\nl 5 6 7 8\n"
    "g fringe\nv 0.02 0 0\nv 0.02 0.05 0\nv 0.021 0.1 0.001\nv 0.02 0.14 0.003\nl 9 10 11 12\n";

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("CLI: usage errors exit 1, invalid input 2, I/O 3", "[baker][cli]") {
  const auto obj = tvk_test::write_text("cli_small.obj", kSmallObj);
  const auto out = tvk_test::temp_dir() / "cli_small.tvkhair";
  CHECK(run_bake("--help") == 0);
  CHECK(run_bake("") == 1);                                         // no input
  CHECK(run_bake(quoted(obj)) == 1);                                // no output
  CHECK(run_bake(quoted(obj) + " -o " + quoted(out) + " --vertices 3") == 1);
  CHECK(run_bake(quoted(obj) + " -o " + quoted(out) + " --vertices 129") == 1);
  CHECK(run_bake(quoted(obj) + " -o " + quoted(out) + " --units furlong") == 1);
  CHECK(run_bake(quoted(obj) + " -o " + quoted(out) + " --bogus") == 1);
  CHECK(run_bake(quoted(tvk_test::write_text("cli_faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")) + " -o " + quoted(out)) == 2);
  CHECK_FALSE(fs::exists(out));
  CHECK(run_bake(quoted(tvk_test::temp_dir() / "missing.obj") + " -o " + quoted(out)) == 3);
  CHECK(run_bake(quoted(obj) + " -o " + quoted(tvk_test::temp_dir() / "no_such_dir" / "x.tvkhair")) == 3);
  CHECK(run_bake(quoted(obj) + " -o " + quoted(out) + " --vertices 5 --follow 2 --units cm --up z --pin 1 --seed 7 -v") == 0);
  CHECK(run_bake("validate " + quoted(out)) == 0);
  CHECK(run_bake("validate " + quoted(tvk_test::temp_dir() / "missing.tvkhair")) == 3);
  CHECK(run_bake("validate " + quoted(obj)) == 2);
}

TEST_CASE("CLI: a failed bake leaves no partial or stale output behind", "[baker][cli]") {
  const auto out = tvk_test::temp_dir() / "stale.tvkhair";
  const auto obj = tvk_test::write_text("stale.obj", kSmallObj);
  REQUIRE(run_bake(quoted(obj) + " -o " + quoted(out)) == 0);
  const auto good = tvk_test::read_bytes(out);
  const auto bad = tvk_test::write_text("stale_bad.obj", kSmallObj + "l 1 99\n");
  CHECK(run_bake(quoted(bad) + " -o " + quoted(out)) == 2);
  CHECK(tvk_test::read_bytes(out) == good);  // the old file is untouched, not half-overwritten
  for (const auto& e : fs::directory_iterator(tvk_test::temp_dir()))
    CHECK(e.path().filename().string().find(".tmp") == std::string::npos);
}

TEST_CASE("CLI: bakes are deterministic (two bakes, identical bytes)", "[baker][cli]") {
  const auto obj = tvk_test::write_text("det.obj", kSmallObj);
  const auto a = tvk_test::temp_dir() / "det_a.tvkhair", b = tvk_test::temp_dir() / "det_b.tvkhair";
  REQUIRE(run_bake(quoted(obj) + " -o " + quoted(a) + " --follow 3 --seed 5") == 0);
  REQUIRE(run_bake(quoted(obj) + " -o " + quoted(b) + " --follow 3 --seed 5") == 0);
  CHECK(tvk_test::read_bytes(a) == tvk_test::read_bytes(b));
  REQUIRE(run_bake(quoted(obj) + " -o " + quoted(b) + " --follow 3 --seed 6") == 0);
  CHECK(tvk_test::read_bytes(a) != tvk_test::read_bytes(b));
  const auto dir = tvk_test::data_dir();
  if (dir.empty()) SKIP("real hair data not found: set TRESSVK_DATA_DIR (the small-file check above still ran)");
  const auto r = dir / "tressfx" / "ratboy";
  const std::string args = quoted(r / "Ratboy_mohawk.tfx") + " --bones " + quoted(r / "Ratboy_mohawk.tfxbone") + " --follow 2 -o ";
  REQUIRE(run_bake(args + quoted(a)) == 0);
  REQUIRE(run_bake(args + quoted(b)) == 0);
  CHECK(tvk_test::read_bytes(a) == tvk_test::read_bytes(b));
}

TEST_CASE("CLI: info --json lists the documented keys", "[baker][cli]") {
  const auto obj = tvk_test::write_text("info.obj", kSmallObj);
  const auto out = tvk_test::temp_dir() / "info.tvkhair";
  const auto json_path = tvk_test::temp_dir() / "info.json";
  REQUIRE(run_bake(quoted(obj) + " -o " + quoted(out) + " --follow 2 --vertices 12") == 0);
  REQUIRE(run_bake("info " + quoted(out) + " --json > " + quoted(json_path), false) == 0);
  const auto j = nlohmann::json::parse(slurp(json_path));
  CHECK(j["format_version"] == "1.0");
  CHECK(j["units"] == "m");
  CHECK(j["guide_strands"] == 3);
  CHECK(j["follow_per_guide"] == 2);
  CHECK(j["total_strands"] == 9);
  CHECK(j["vertices_per_strand"] == 12);
  CHECK(j["total_vertices"] == 108);
  REQUIRE(j["groups"].size() == 2);
  CHECK(j["groups"][0]["name"] == "crown");
  CHECK(j["groups"][0]["strands"] == 6);
  CHECK(j["groups"][1]["name"] == "fringe");
  CHECK(j["groups"][1]["strands"] == 3);
  CHECK(j["bounds"]["min"].size() == 3);
  CHECK(j["bounds"]["max"].size() == 3);
  CHECK(j["checksums_ok"] == true);
  REQUIRE(j["sections"].size() >= 7);
  for (const auto& s : j["sections"]) {
    CHECK(s.contains("name"));
    CHECK(s.contains("offset"));
    CHECK(s.contains("size"));
    CHECK(s.contains("checksum"));
    CHECK(s["offset"].get<uint64_t>() % 64 == 0);
  }
  CHECK(run_bake("info " + quoted(out)) == 0);
}

TEST_CASE("CLI: info --json stays valid JSON for odd names and hand-made settings", "[baker][cli]") {
  auto a = baker::bake(baker::import_obj_text(kSmallObj, "odd.obj"), {});
  a.groups[0].name = "caf\xE9 \xFF";  // Latin-1 bytes, not UTF-8
  a.bake_settings = "made by hand";
  const auto path = tvk_test::temp_dir() / "odd.tvkhair";
  REQUIRE(asset::write_file(path, a).empty());
  const auto json_path = tvk_test::temp_dir() / "odd.json";
  REQUIRE(run_bake("info " + quoted(path) + " --json > " + quoted(json_path), false) == 0);
  const auto j = nlohmann::json::parse(slurp(json_path));
  CHECK(j["bake_settings"] == "made by hand");
  CHECK(j["groups"].size() == 2);
}

TEST_CASE("CLI: --report writes the bake statistics", "[baker][cli]") {
  const auto obj = tvk_test::write_text("report.obj", kSmallObj + "v 5 0 0\nv 5 0.0000001 0\nl 13 14\n");
  const auto out = tvk_test::temp_dir() / "report.tvkhair";
  const auto rep = tvk_test::temp_dir() / "report.json";
  REQUIRE(run_bake(quoted(obj) + " -o " + quoted(out) + " --report " + quoted(rep)) == 0);
  const auto j = nlohmann::json::parse(slurp(rep));
  CHECK(j["input"]["strands"] == 4);
  CHECK(j["input"]["dropped_short"] == 1);
  CHECK(j["output"]["guide_strands"] == 3);
  CHECK(j["resampling_error"]["max_m"].get<double>() >= 0.0);
}

TEST_CASE("CLI: validate detects a flipped byte anywhere in the file", "[baker][cli]") {
  const auto obj = tvk_test::write_text("flip.obj", kSmallObj);
  const auto good = tvk_test::temp_dir() / "flip.tvkhair";
  REQUIRE(run_bake(quoted(obj) + " -o " + quoted(good) + " --follow 1 --vertices 6") == 0);
  const auto bytes = tvk_test::read_bytes(good);
  const auto info = asset::inspect(bytes).info;
  // One flip in the header, one in the table, one in every section, one in padding (CLI runs are slow;
  // format_test flips far more bytes in-process).
  std::vector<size_t> where{9, 70};
  for (const auto& s : info.sections)
    if (s.size) where.push_back(static_cast<size_t>(s.offset + s.size / 2));
  where.push_back(static_cast<size_t>(info.sections.front().offset - 1));
  const auto bad = tvk_test::temp_dir() / "flip_bad.tvkhair";
  for (size_t at : where) {
    auto b = bytes;
    b[at] ^= std::byte{0x10};
    tvk_test::write_bytes(bad, b);
    INFO("flipped byte " << at);
    CHECK(run_bake("validate " + quoted(bad)) == 2);
    CHECK(run_bake("info " + quoted(bad)) == 2);
  }
}

TEST_CASE("CLI: export -> bake round trip", "[baker][cli]") {
  const auto obj = tvk_test::write_text("rt.obj", kSmallObj);
  const auto first = tvk_test::temp_dir() / "rt1.tvkhair", second = tvk_test::temp_dir() / "rt2.tvkhair";
  const auto exported = tvk_test::temp_dir() / "rt_export.obj", with_follows = tvk_test::temp_dir() / "rt_follow.obj";
  REQUIRE(run_bake(quoted(obj) + " -o " + quoted(first) + " --vertices 9 --follow 2") == 0);
  REQUIRE(run_bake("export " + quoted(first) + " -o " + quoted(exported)) == 0);
  REQUIRE(run_bake(quoted(exported) + " -o " + quoted(second) + " --vertices 9 --keep-order") == 0);
  const auto a = asset::read_file(first), b = asset::read_file(second);
  REQUIRE(a.ok());
  REQUIRE(b.ok());
  REQUIRE(a.asset.guide_count() == b.asset.guide_count());
  CHECK(a.asset.groups.size() == b.asset.groups.size());
  // The export is in the first asset's (shuffled) order and re-baking keeps it. Roots and tips come back
  // exactly (to float32 at the groom's extent). Interior vertices may slide along the strand: the first bake
  // spaced them evenly in the *input's* arc length, so the chords of a curved strand differ slightly and the
  // second bake, spacing evenly along those chords, moves them by a small fraction of a segment (measured:
  // 1.7e-6 m on 1.9 cm segments, 9e-5 of a segment); allow 5e-4 of the segment length.
  for (uint32_t g = 0; g < a.asset.guide_count(); ++g) {
    const double segment = tvk_test::guide_length(a.asset, g) / 8;
    for (uint32_t v = 0; v < 9; ++v) {
      const double d = tvk_test::distance(tvk_test::position(a.asset, g, v), tvk_test::position(b.asset, g, v));
      CHECK(d < ((v == 0 || v == 8) ? 1e-7 : 5e-4 * segment));
    }
  }
  // With --follow: guides and follows, G * (K + 1) strands.
  REQUIRE(run_bake("export " + quoted(first) + " -o " + quoted(with_follows) + " --follow") == 0);
  const auto raw = baker::import_obj(with_follows);
  CHECK(raw.strand_count() == 9);
}

#ifdef TRESSVK_BUILD_TIME_BAKE
TEST_CASE("CMake: tressvk_bake_hair baked a valid asset at build time", "[baker][cmake]") {
  const auto r = asset::read_file(TRESSVK_BUILD_TIME_BAKE);
  REQUIRE(r.ok());
  CHECK(r.asset.guide_count() == 2);
  CHECK(r.asset.vertices_per_strand == 6);
  CHECK(r.asset.follow_per_guide == 1);
  CHECK(r.asset.groups.front().name == "tiny");
}
#endif
