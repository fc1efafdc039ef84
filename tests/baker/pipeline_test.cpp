// The bake pipeline against the conventions documented in asset.hpp, checked independently of its code.
#include "test_support.hpp"

#include <tressvk/baker/errors.hpp>
#include <tressvk/baker/procedural.hpp>

#include <catch2/catch_approx.hpp>
#include <catch2/generators/catch_generators.hpp>

#include <cmath>
#include <set>

using namespace tressvk;
using Catch::Approx;
using V3 = std::array<double, 3>;

namespace {

V3 rotate(const std::array<float, 4>& q, const V3& v) {
  const V3 u{q[0], q[1], q[2]};
  const double w = q[3];
  auto cross = [](const V3& a, const V3& b) {
    return V3{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  };
  const V3 c1 = cross(u, v);
  const V3 t{2 * c1[0], 2 * c1[1], 2 * c1[2]};
  const V3 c2 = cross(u, t);
  return {v[0] + w * t[0] + c2[0], v[1] + w * t[1] + c2[1], v[2] + w * t[2] + c2[2]};
}

V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double norm(const V3& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

// A wavy strand written with uneven segment lengths, to make resampling do real work.
std::string wavy_obj(int points, double length) {
  std::string s;
  for (int i = 0; i < points; ++i) {
    const double t = std::pow(static_cast<double>(i) / (points - 1), 1.7);  // uneven spacing
    s += "v " + std::to_string(0.01 * std::sin(9 * t)) + " " + std::to_string(length * t) + " " +
         std::to_string(0.01 * std::cos(7 * t)) + "\n";
  }
  s += "l";
  for (int i = 1; i <= points; ++i) s += " " + std::to_string(i);
  return s + "\n";
}

}  // namespace

TEST_CASE("Resampling: any N from 4 to 128, even arc-length spacing, root and tip kept", "[baker][pipeline]") {
  const uint32_t n = GENERATE(4u, 5u, 7u, 13u, 32u, 100u, 128u);
  baker::BakeOptions o;
  o.vertices_per_strand = n;
  const auto a = tvk_test::bake_obj(wavy_obj(200, 0.3), o);
  REQUIRE(a.vertices_per_strand == n);
  REQUIRE(a.guide_count() == 1);
  REQUIRE(tressvk::asset::validate(a).empty());
  CHECK(tvk_test::distance(tvk_test::position(a, 0, 0), {0.0, 0.0, 0.01}) < 1e-6);
  // Every edge spans the same arc length: chords of equal arcs on a gently curved strand are nearly equal
  // (the curvature makes the chord shorter than the arc by at most a few percent at N = 4).
  const double mean = tvk_test::guide_length(a, 0) / (n - 1);
  for (uint32_t v = 0; v + 1 < n; ++v) CHECK(a.rest_lengths[v] == Approx(mean).epsilon(0.05));
}

TEST_CASE("Pins and inverse masses", "[baker][pipeline]") {
  baker::BakeOptions o;
  o.pin = 3;
  const auto a = tvk_test::bake_obj(wavy_obj(50, 0.2), o);
  for (uint32_t v = 0; v < a.vertices_per_strand; ++v) CHECK(a.rest_positions[v][3] == (v < 3 ? 0.0f : 1.0f));
}

TEST_CASE("Rest frames follow the documented parallel-transport convention", "[baker][pipeline]") {
  const auto a = tvk_test::bake_obj(wavy_obj(200, 0.3));
  const uint32_t n = a.vertices_per_strand;
  for (uint32_t v = 0; v < n; ++v) {
    const auto& q = a.rest_frames[v];
    const V3 p0{a.rest_positions[v][0], a.rest_positions[v][1], a.rest_positions[v][2]};
    // frame[v] +X is along the edge arriving at v (frame[0]: the root edge).
    const uint32_t from = v == 0 ? 0 : v - 1;
    const V3 e_in = sub({a.rest_positions[from + 1][0], a.rest_positions[from + 1][1], a.rest_positions[from + 1][2]},
                        {a.rest_positions[from][0], a.rest_positions[from][1], a.rest_positions[from][2]});
    const V3 x = rotate(q, {1, 0, 0});
    CHECK(x[0] * e_in[0] + x[1] * e_in[1] + x[2] * e_in[2] == Approx(norm(e_in)).epsilon(1e-5));
    if (v + 1 < n) {
      // rest_edge_local[v] turned by frame[v] gives back the edge leaving v.
      const V3 e_out = sub({a.rest_positions[v + 1][0], a.rest_positions[v + 1][1], a.rest_positions[v + 1][2]}, p0);
      const auto& l = a.rest_edge_local[v];
      const V3 back = rotate(q, {l[0], l[1], l[2]});
      CHECK(norm(sub(back, e_out)) < 1e-5 * norm(e_out));
    }
  }
  // rest_edge_local[0] = (|p1 - p0|, 0, 0).
  CHECK(a.rest_edge_local[0][0] == Approx(a.rest_lengths[0]).epsilon(1e-6));
  CHECK(std::abs(a.rest_edge_local[0][1]) < 1e-6f * a.rest_lengths[0]);
  CHECK(std::abs(a.rest_edge_local[0][2]) < 1e-6f * a.rest_lengths[0]);
  // Consecutive frames differ by the minimal rotation: no twist about the edge (frame v's +Y stays
  // perpendicular to the edge and has no component along the binormal rotation axis beyond the bend).
  for (uint32_t v = 2; v < n; ++v) {
    const V3 x0 = rotate(a.rest_frames[v - 1], {1, 0, 0}), x1 = rotate(a.rest_frames[v], {1, 0, 0});
    const V3 y0 = rotate(a.rest_frames[v - 1], {0, 1, 0}), y1 = rotate(a.rest_frames[v], {0, 1, 0});
    // The minimal rotation keeps the component of Y along the rotation axis x0 x x1 unchanged.
    V3 axis{x0[1] * x1[2] - x0[2] * x1[1], x0[2] * x1[0] - x0[0] * x1[2], x0[0] * x1[1] - x0[1] * x1[0]};
    const double s = norm(axis);
    if (s < 1e-6) continue;
    axis = {axis[0] / s, axis[1] / s, axis[2] / s};
    CHECK(y0[0] * axis[0] + y0[1] * axis[1] + y0[2] * axis[2] ==
          Approx(y1[0] * axis[0] + y1[1] * axis[1] + y1[2] * axis[2]).margin(1e-5));
  }
}

TEST_CASE("Root frame: +Y from the asset axis least aligned with the root edge, ties X, Y, Z", "[baker][pipeline]") {
  // Root edge along +X: Y and Z tie (both perpendicular) -> +Y, so frame[0] is the identity.
  const auto a = tvk_test::bake_obj("v 0 0 0\nv 0.1 0 0\nv 0.2 0 0\nv 0.3 0 0\nl 1 2 3 4\n");
  const auto& q = a.rest_frames[0];
  CHECK(std::abs(q[0]) < 1e-7f);
  CHECK(std::abs(q[1]) < 1e-7f);
  CHECK(std::abs(q[2]) < 1e-7f);
  CHECK(std::abs(q[3]) == Approx(1.0f));
  // Root edge along +Y: X and Z tie -> +X becomes local +Y.
  const auto b = tvk_test::bake_obj("v 0 0 0\nv 0 0.1 0\nv 0 0.2 0\nv 0 0.3 0\nl 1 2 3 4\n");
  const V3 y = rotate(b.rest_frames[0], {0, 1, 0});
  CHECK(y[0] == Approx(1.0).margin(1e-6));
}

TEST_CASE("Units, scale and up axis are applied before anything else", "[baker][pipeline]") {
  const std::string text = "v 0 0 0\nv 0 0 10\nv 0 0 20\nv 0 0 30\nl 1 2 3 4\n";  // 30 units along +Z
  baker::BakeOptions o;
  o.units_to_metres = 0.01;  // cm
  o.up = baker::UpAxis::kZ;
  o.vertices_per_strand = 4;
  const auto a = tvk_test::bake_obj(text, o);
  const auto tip = tvk_test::position(a, 0, 3);
  CHECK(tip[0] == Approx(0.0).margin(1e-9));
  CHECK(tip[1] == Approx(0.3).epsilon(1e-6));  // Z up -> Y up
  CHECK(tip[2] == Approx(0.0).margin(1e-9));
  o.scale = 2.0;
  CHECK(tvk_test::position(tvk_test::bake_obj(text, o), 0, 3)[1] == Approx(0.6).epsilon(1e-6));
}

TEST_CASE("Positions are relative to an origin at the bounds centre rounded to a millimetre", "[baker][pipeline]") {
  // A groom 1 km from the world origin keeps sub-micrometre detail.
  const std::string text = "v 1000.0001234 5 0\nv 1000.0001234 5.1 0\nv 1000.0001234 5.2 0.0000005\nl 1 2 3\n";
  baker::BakeOptions o;
  o.vertices_per_strand = 4;
  const auto a = tvk_test::bake_obj(text, o);
  CHECK(a.origin[0] == 1000.0);
  CHECK(a.origin[1] == Approx(5.1));
  CHECK(tvk_test::position(a, 0, 0)[0] == Approx(1000.0001234).margin(1e-8));
  CHECK(tvk_test::position(a, 0, 3)[2] == Approx(0.0000005).margin(1e-9));
}

TEST_CASE("Degenerate geometry: repeated vertices merged, tiny strands dropped and counted", "[baker][pipeline]") {
  std::string text;
  // Strand 1: 0.2 long with a repeated vertex and a sub-micrometre segment; strand 2: 1 micrometre long.
  text += "v 0 0 0\nv 0 0.1 0\nv 0 0.1 0\nv 0 0.1000000001 0\nv 0 0.2 0\nl 1 2 3 4 5\n";
  text += "v 1 0 0\nv 1 0.000001 0\nl 6 7\n";
  text += "v 2 0 0\nv 2 0.1 0\nv 2 0.2 0\nl 8 9 10\n";
  baker::BakeReport rep;
  baker::BakeOptions o;
  o.shuffle = false;
  const auto a = baker::bake(baker::import_obj_text(text, "t.obj"), o, &rep);
  CHECK(a.guide_count() == 2);
  CHECK(rep.dropped_short == 1);
  CHECK(rep.merged_vertices == 3);  // the repeat and the 1e-10 segment, and the short strand's tip
  CHECK(tressvk::asset::validate(a).empty());
  CHECK(tvk_test::guide_length(a, 0) == Approx(0.2).epsilon(1e-6));
  // Everything degenerate: a clear error, not an empty asset.
  CHECK_THROWS_AS(baker::bake(baker::import_obj_text("v 0 0 0\nv 0 0 0\nl 1 2\n", "t.obj"), o), baker::InputError);
}

TEST_CASE("Thresholds scale with the groom: the same groom in mm and in km bakes alike", "[baker][pipeline]") {
  std::string text = wavy_obj(100, 0.3) + "v 1 0 0\nv 1 0.0000001 0\nl 101 102\n";
  baker::BakeOptions o;
  o.shuffle = false;
  baker::BakeReport r1, r2;
  o.units_to_metres = 0.001;
  const auto a = baker::bake(baker::import_obj_text(text, "t.obj"), o, &r1);
  o.units_to_metres = 1000.0;
  const auto b = baker::bake(baker::import_obj_text(text, "t.obj"), o, &r2);
  CHECK(a.guide_count() == b.guide_count());
  CHECK(r1.dropped_short == r2.dropped_short);
  CHECK(r1.merged_vertices == r2.merged_vertices);
  CHECK(r2.max_relative_resample_error == Approx(r1.max_relative_resample_error).epsilon(1e-6));
}

TEST_CASE("Follow hairs: offsets in the root frame, perpendicular to the root edge, within the radius", "[baker][pipeline]") {
  baker::BakeOptions o;
  o.follow_per_guide = 3;
  o.follow_radius = 0.01;
  o.tip_separation = 1.5f;
  const auto a = tvk_test::bake_obj(wavy_obj(60, 0.2), o);
  REQUIRE(a.follow_offsets.size() == a.guide_count() * 3);
  CHECK(a.tip_separation == 1.5f);
  for (const auto& f : a.follow_offsets) {
    CHECK(f[0] == 0.0f);  // local +X is the root edge
    CHECK(std::hypot(f[1], f[2]) <= 0.01f * 1.000001f);
    CHECK(f[3] == 0.0f);
  }
}

TEST_CASE("LOD order: seeded, deterministic, and prefixes thin the groom evenly by height", "[baker][pipeline]") {
  baker::BuiltinGroomOptions o;
  o.guide_count = 2048;
  const auto a = baker::make_builtin_groom("straight", o);
  const auto b = baker::make_builtin_groom("straight", o);
  CHECK(a.rest_positions == b.rest_positions);
  o.seed = 2;
  CHECK(baker::make_builtin_groom("straight", o).rest_positions != a.rest_positions);
  // Roots are spread evenly over the hemisphere by height; a prefix of 1/8 of the guides must cover the
  // height bands in proportion (each of 8 bands holds 1/8 of the roots; allow binomial noise of ~4 sigma).
  const size_t prefix = a.guide_count() / 8;
  std::array<int, 8> bands{};
  for (size_t s = 0; s < prefix; ++s) {
    const double y = tvk_test::position(a, static_cast<uint32_t>(s), 0)[1] / 0.1;
    bands[std::min<size_t>(7, static_cast<size_t>(std::max(0.0, y) * 8))]++;
  }
  for (int c : bands) CHECK(std::abs(c - static_cast<int>(prefix) / 8) <= 4 * 6);  // sigma = sqrt(256*7/64) ~ 5.3
}

TEST_CASE("LOD order: every prefix covers the scalp without holes", "[baker][pipeline]") {
  baker::BuiltinGroomOptions o;
  o.guide_count = 2048;
  const auto a = baker::make_builtin_groom("straight", o);
  const uint32_t g = a.guide_count();
  std::vector<V3> roots(g);
  for (uint32_t i = 0; i < g; ++i) roots[i] = tvk_test::position(a, i, 0);
  for (size_t m : {16, 64, 256, 1024}) {
    // Coverage radius: the largest distance from any root to the nearest root of the prefix, relative to the
    // ideal spacing sqrt(area / m) of m roots on the hemisphere. Measured for this order: 0.97-1.22 over
    // prefixes 16..1024; a uniformly random shuffle measures 1.13-1.59 (holes), so 1.35 separates the two.
    double worst = 0;
    for (const auto& p : roots) {
      double best = 1e9;
      for (size_t j = 0; j < m; ++j) best = std::min(best, norm(sub(p, roots[j])));
      worst = std::max(worst, best);
    }
    INFO("prefix " << m);
    CHECK(worst / std::sqrt(2 * 3.14159265358979 * 0.01 / static_cast<double>(m)) < 1.35);
  }
}

TEST_CASE("Built-in grooms", "[baker][procedural]") {
  REQUIRE(baker::builtin_groom_names() == std::vector<std::string>{"straight", "curly", "long128"});
  for (const auto& name : baker::builtin_groom_names()) {
    baker::BuiltinGroomOptions o;
    o.guide_count = 300;
    o.follow_per_guide = 2;
    const auto a = baker::make_builtin_groom(name, o);
    INFO(name);
    CHECK(tressvk::asset::validate(a).empty());
    CHECK(a.guide_count() == 300);
    CHECK(a.follow_per_guide == 2);
    CHECK(a.vertices_per_strand == (name == "long128" ? 128u : 32u));
    for (uint32_t g = 0; g < a.guide_count(); ++g) {
      const auto root = tvk_test::position(a, g, 0);
      // Roots on the upper half of the head sphere (radius 0.1 m, centre at the origin).
      CHECK(norm(root) == Approx(0.1).margin(1e-6));
      CHECK(root[1] >= 0.0);
      const double len = tvk_test::guide_length(a, g);
      if (name == "straight") CHECK(len == Approx(0.15).epsilon(1e-4));
      if (name == "long128") CHECK(len == Approx(0.5).epsilon(0.01));
    }
  }
  // Curly: 32 vertices over about 7.5 turns of a 1 cm helix (chords cut the curls: length below the arc).
  baker::BuiltinGroomOptions o;
  o.guide_count = 16;
  o.vertices_per_strand = 128;
  const auto c = baker::make_builtin_groom("curly", o);
  const double turn = std::hypot(2 * 3.14159265358979 * 0.01, 0.02);
  CHECK(tvk_test::guide_length(c, 0) == Approx(turn * 0.15 / 0.02).epsilon(0.03));
  CHECK_THROWS_AS(baker::make_builtin_groom("bald", {}), std::invalid_argument);
}
