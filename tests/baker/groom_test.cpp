// The groom generator (tressvk-bake groom): determinism, roots on the scalp and spread by area, the groomers'
// controls each doing what it says (parting, length and length map, gravity, clumping, curl), the face kept
// clear, and bad input giving a clear error, a distinct exit code and no output.
//
// The scalp is the upper half of a sphere of radius 0.1 m at the origin (the face towards +Z), built here.
#include "test_support.hpp"

#include <tressvk/baker/errors.hpp>
#include <tressvk/baker/groom.hpp>

#include <catch2/catch_approx.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>

using namespace tressvk;
using tvk_test::quoted;
using tvk_test::run_bake;
namespace fs = std::filesystem;

namespace {

constexpr double kR = 0.1;
constexpr double kPi = 3.14159265358979323846;

// A latitude-longitude cap of the sphere from the top down to `lowest_y` (times the radius).
baker::GroomScalp sphere_scalp(double lowest_y = 0.0, double colour = -1.0) {
  baker::GroomScalp s;
  const int rings = 24, segs = 48;
  const double theta_max = std::acos(lowest_y);
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j < segs; ++j) {
      const double th = theta_max * i / rings, ph = 2 * kPi * j / segs;
      s.vertices.push_back({kR * std::sin(th) * std::sin(ph), kR * std::cos(th), kR * std::sin(th) * std::cos(ph)});
      if (colour >= 0) s.length_map.push_back(colour);
    }
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segs; ++j) {
      const uint32_t a = i * segs + j, b = i * segs + (j + 1) % segs, c = a + segs, d = b + segs;
      s.triangles.push_back({a, c, b});
      s.triangles.push_back({b, c, d});
    }
  return s;
}

baker::GroomParams small(const char* preset) {
  baker::GroomParams p = baker::groom_preset(preset);
  p.guides = 400;
  p.follow = 1;
  return p;
}

double polyline_length(const baker::RawGroom& g, size_t s) {
  double l = 0;
  for (uint32_t k = g.strand_begin[s] + 1; k < g.strand_begin[s + 1]; ++k)
    l += tvk_test::distance(g.points[k], g.points[k - 1]);
  return l;
}

std::vector<std::byte> bytes_of(const asset::HairAsset& a) { return asset::write(a); }

}  // namespace

TEST_CASE("groom: the same scalp, preset and seed give the same bytes; another seed other hair", "[baker][groom]") {
  const auto scalp = sphere_scalp();
  const auto a = baker::make_groom(scalp, small("straight"), "straight");
  const auto b = baker::make_groom(scalp, small("straight"), "straight");
  CHECK(bytes_of(a) == bytes_of(b));
  baker::GroomParams other = small("straight");
  other.seed = 2;
  CHECK(bytes_of(baker::make_groom(scalp, other, "straight")) != bytes_of(a));
  CHECK(asset::validate(a).empty());
  CHECK(a.guide_count() == 400);
  CHECK(a.follow_per_guide == 1);
  // The groom's own settings are recorded (taper for the host's material).
  const auto settings = nlohmann::json::parse(a.bake_settings);
  CHECK(settings["groom"]["preset"] == "straight");
  CHECK(settings["groom"]["taper"].get<double>() == Catch::Approx(baker::groom_preset("straight").taper));
}

TEST_CASE("groom: roots lie on the scalp and are spread by area", "[baker][groom]") {
  const auto scalp = sphere_scalp();
  const auto g = baker::grow_groom(scalp, small("straight"));
  REQUIRE(g.strand_count() == 400);
  baker::ScalpMesh mesh{scalp.vertices, scalp.triangles};
  uint32_t front = 0, top = 0;
  for (size_t s = 0; s < g.strand_count(); ++s) {
    const auto& root = g.points[g.strand_begin[s]];
    // On the (faceted) sphere: within float-free double rounding of a face.
    CHECK(baker::distance_to_scalp_brute_force(root, mesh) < 1e-9);
    if (root[2] > 0) ++front;
    if (root[1] > 0.5 * kR) ++top;
  }
  // Area-weighted: half the cap's area is in front (z > 0); the zone above y = r/2 holds half the hemisphere's
  // area (a sphere zone's area is proportional to its height). Stratified placement keeps both within 4 %.
  CHECK(std::abs(front / 400.0 - 0.5) < 0.04);
  CHECK(std::abs(top / 400.0 - 0.5) < 0.04);
}

TEST_CASE("groom: strands part away from the parting and straight hair falls", "[baker][groom]") {
  const auto scalp = sphere_scalp();
  baker::GroomParams p = small("straight");
  p.parting = 0.3;  // the line x = 0.03 m over the top
  const auto g = baker::grow_groom(scalp, p);
  uint32_t near_top = 0, away = 0, falls = 0;
  for (size_t s = 0; s < g.strand_count(); ++s) {
    const auto& root = g.points[g.strand_begin[s]];
    const auto& tip = g.points[g.strand_begin[s + 1] - 1];
    if (tip[1] < root[1] - 0.3 * p.length) ++falls;
    if (root[1] < 0.8 * kR || std::abs(root[0] - 0.03) < 0.005) continue;
    ++near_top;
    // A quarter of the way along, the strand has moved to its own side of the parting.
    const auto& q = g.points[g.strand_begin[s] + (g.strand_begin[s + 1] - g.strand_begin[s]) / 4];
    if ((q[0] - root[0]) * (root[0] - 0.03) > 0) ++away;
  }
  REQUIRE(near_top > 40);
  INFO(away << " of " << near_top << " strands near the top move away from the parting");
  CHECK(away >= 0.95 * near_top);
  INFO(falls << " of 400 strands end well below their root");
  CHECK(falls >= 0.95 * 400);
}

TEST_CASE("groom: length, length variation and the length map", "[baker][groom]") {
  baker::GroomParams p = small("straight");
  p.length_variation = 0.0;
  p.frizz = 0.0;
  p.clump = 0.0;
  const auto full = baker::grow_groom(sphere_scalp(), p);
  const auto half = baker::grow_groom(sphere_scalp(0.0, 0.5), p);  // vertex colour 0.5 everywhere
  double full_sum = 0, half_sum = 0, lo = 1e9, hi = 0;
  for (size_t s = 0; s < full.strand_count(); ++s) {
    const double l = polyline_length(full, s);
    full_sum += l;
    lo = std::min(lo, l);
    hi = std::max(hi, l);
    half_sum += polyline_length(half, s);
  }
  // Growth keeps the step length; only the last pass that keeps strands out of the head and off the face moves
  // points after it, shortening or lengthening a strand by a few per cent (measured: 7 % of the length between
  // the shortest and the longest, 0.3 % on the mean), far less than the variation tested below.
  CHECK(full_sum / 400 == Catch::Approx(p.length).epsilon(0.02));
  CHECK(hi - lo < 0.1 * p.length);
  CHECK(half_sum / full_sum == Catch::Approx(0.5).epsilon(0.02));
  p.length_variation = 0.3;
  const auto varied = baker::grow_groom(sphere_scalp(), p);
  double vlo = 1e9, vhi = 0;
  for (size_t s = 0; s < varied.strand_count(); ++s) {
    vlo = std::min(vlo, polyline_length(varied, s));
    vhi = std::max(vhi, polyline_length(varied, s));
  }
  CHECK(vhi - vlo > 0.4 * p.length);  // up to 0.6 x length apart
}

TEST_CASE("groom: curl makes ringlets, clumping gathers the tips", "[baker][groom]") {
  const auto scalp = sphere_scalp();
  // Curl: the strand's length over the distance it covers.
  auto tortuosity = [](const baker::RawGroom& g) {
    double sum = 0;
    for (size_t s = 0; s < g.strand_count(); ++s)
      sum += polyline_length(g, s) /
             tvk_test::distance(g.points[g.strand_begin[s]], g.points[g.strand_begin[s + 1] - 1]);
    return sum / static_cast<double>(g.strand_count());
  };
  baker::GroomParams straight = small("straight");
  baker::GroomParams curly = small("curly");
  const double t_straight = tortuosity(baker::grow_groom(scalp, straight));
  const double t_curly = tortuosity(baker::grow_groom(scalp, curly));
  INFO("tortuosity straight " << t_straight << ", curly " << t_curly);
  CHECK(t_curly > 1.3 * t_straight);

  // Clumping: tips closer to their nearest neighbour than without clumps (roots are where they were).
  auto tip_spacing = [](const baker::RawGroom& g) {
    double sum = 0;
    for (size_t s = 0; s < g.strand_count(); ++s) {
      double best = 1e9;
      const auto& a = g.points[g.strand_begin[s + 1] - 1];
      for (size_t t = 0; t < g.strand_count(); ++t)
        if (t != s) best = std::min(best, tvk_test::distance(a, g.points[g.strand_begin[t + 1] - 1]));
      sum += best;
    }
    return sum / static_cast<double>(g.strand_count());
  };
  straight.clump = 0.0;
  const double loose = tip_spacing(baker::grow_groom(scalp, straight));
  straight.clump = 0.9;
  const double clumped = tip_spacing(baker::grow_groom(scalp, straight));
  INFO("mean nearest tip distance: no clumps " << loose << " m, clump 0.9 " << clumped << " m");
  CHECK(clumped < 0.5 * loose);
}

TEST_CASE("groom: no strand hangs in front of the face", "[baker][groom]") {
  // Curls with lift and strands from the hairline would fall forwards over the face without the face rule.
  const auto scalp = sphere_scalp(0.0);
  for (const char* preset : {"straight", "curly"}) {
    const auto g = baker::grow_groom(scalp, small(preset));
    uint32_t in_front = 0;
    for (size_t s = 0; s < g.strand_count(); ++s)
      for (uint32_t k = g.strand_begin[s] + 1; k < g.strand_begin[s + 1]; ++k) {  // roots stay where they grow
        const auto& p = g.points[k];
        if (p[2] > 0.3 * kR && p[1] < 0.0 && p[1] > -1.2 * kR && std::abs(p[0]) < 0.6 * kR) ++in_front;
      }
    INFO(preset << ": " << in_front << " points in front of the face");
    CHECK(in_front == 0);
  }
}

TEST_CASE("groom: scalp OBJ parsing, vertex colours and errors naming the file and line", "[baker][groom]") {
  const auto s = baker::parse_groom_scalp("# scalp\nv 0 0 0 1 1 1\nv 1 0 0\nv 0 1 0 0.5 0.5 0.5\nf 1/1/1 2//2 3\n",
                                          "s.obj");
  REQUIRE(s.triangles.size() == 1);
  REQUIRE(s.length_map.size() == 3);
  CHECK(s.length_map[1] == 1.0);  // a vertex without a colour takes the full length
  CHECK(s.length_map[2] == 0.5);
  CHECK(baker::parse_groom_scalp("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf -4 -3 -2 -1\n", "q.obj").triangles.size() == 2);
  auto error_of = [](const std::string& text) {
    try {
      baker::parse_groom_scalp(text, "bad.obj");
    } catch (const baker::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(error_of("v 0 0 0\nv 1 0 0\nl 1 2\n").find("bad.obj: the scalp has no faces") != std::string::npos);
  CHECK(error_of("v 0 0 0\nv 1 0 x\n").find("bad.obj:2:") != std::string::npos);
  CHECK(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 9\n").find("bad.obj:5: vertex index 9 is out of range") !=
        std::string::npos);
  CHECK(error_of("v 0 0 0\nf 1 1\n").find("bad.obj:2:") != std::string::npos);
  CHECK(error_of("v 0 0 0 nan 1 1\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").find("bad.obj:1:") != std::string::npos);
  // Faces without area are no scalp either.
  baker::GroomScalp flat;
  flat.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  flat.triangles = {{0, 1, 2}};
  CHECK_THROWS_AS(baker::grow_groom(flat, small("straight")), baker::InputError);
  CHECK_THROWS_AS(baker::groom_preset("mohawk"), baker::InputError);
  baker::GroomParams bad = small("straight");
  bad.clump = 1.5;
  CHECK_THROWS_AS(baker::grow_groom(sphere_scalp(), bad), baker::InputError);
}

TEST_CASE("groom CLI: one command, byte-identical output, distinct exit codes and no partial output", "[baker][groom][cli]") {
  const auto scalp = tvk_test::write_text("groom_scalp.obj", baker::groom_scalp_obj(sphere_scalp(-0.2, 0.8)));
  const auto out = tvk_test::temp_dir() / "groom.tvkhair";
  const auto out2 = tvk_test::temp_dir() / "groom2.tvkhair";
  const std::string base = "groom --scalp " + quoted(scalp) + " --guides 300 --follow 2 ";
  REQUIRE(run_bake(base + "--preset straight -o " + quoted(out)) == 0);
  REQUIRE(run_bake(base + "--preset straight -o " + quoted(out2)) == 0);
  CHECK(tvk_test::read_bytes(out) == tvk_test::read_bytes(out2));
  CHECK(run_bake("validate " + quoted(out)) == 0);
  // Options override the preset: a different seed, curls, no parting.
  REQUIRE(run_bake(base + "--preset curly --seed 9 --parting none --curl-radius 0.005 --curl-frequency 30 "
                   "--frizz 0.001 --clump 0.5 --clump-size 4 --length 0.2 --length-variation 0.1 --gravity 0.5 "
                   "--lift 0.3 --taper 0.4 --vertices 40 -o " + quoted(out2)) == 0);
  const auto curly = asset::read(tvk_test::read_bytes(out2));
  REQUIRE(curly.ok());
  CHECK(curly.asset.vertices_per_strand == 40);
  const auto settings = nlohmann::json::parse(curly.asset.bake_settings)["groom"];
  CHECK(settings["preset"] == "curly");
  CHECK(settings["parting"].is_null());
  CHECK(settings["length_map"] == true);
  CHECK(settings["taper"].get<double>() == Catch::Approx(0.4));

  const auto bad_out = tvk_test::temp_dir() / "groom_bad.tvkhair";
  // 1: usage (bad option values, unknown preset, missing required options).
  CHECK(run_bake(base + "--preset straight --clump 2 -o " + quoted(bad_out)) == 1);
  CHECK(run_bake(base + "--preset straight --parting left -o " + quoted(bad_out)) == 1);
  CHECK(run_bake(base + "--preset straight --guides 0 -o " + quoted(bad_out)) == 1);
  CHECK(run_bake(base + "--preset mohawk -o " + quoted(bad_out)) == 1);
  CHECK(run_bake("groom --preset straight -o " + quoted(bad_out)) == 1);
  // 2: invalid input (a scalp with no faces, a malformed record).
  const auto curves = tvk_test::write_text("groom_curves.obj", "v 0 0 0\nv 0 1 0\nl 1 2\n");
  CHECK(run_bake("groom --scalp " + quoted(curves) + " --preset straight -o " + quoted(bad_out)) == 2);
  const auto broken = tvk_test::write_text("groom_broken.obj", "v 0 0 0\nv 1 0\nf 1 2 3\n");
  CHECK(run_bake("groom --scalp " + quoted(broken) + " --preset straight -o " + quoted(bad_out)) == 2);
  // 3: I/O (a missing scalp, an output directory that does not exist).
  CHECK(run_bake("groom --scalp " + quoted(tvk_test::temp_dir() / "nope.obj") + " --preset straight -o " +
                 quoted(bad_out)) == 3);
  CHECK(run_bake(base + "--preset straight -o " + quoted(tvk_test::temp_dir() / "no_dir" / "x.tvkhair")) == 3);
  CHECK_FALSE(fs::exists(bad_out));
  for (const auto& e : fs::directory_iterator(tvk_test::temp_dir()))
    CHECK(e.path().filename().string().find(".tmp") == std::string::npos);
}
