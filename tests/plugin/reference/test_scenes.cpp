// The scripted scenes at default settings, on the reference: health and stretch bounds of the acceptance, and
// what each scene turns on.
#include <catch2/catch_test_macros.hpp>

#include "helpers.hpp"

using namespace tvk_test;

TEST_CASE("scenes: every scene stays healthy with stretch below 5% on every built-in groom", "[reference][scenes]") {
  for (const char* name : {"straight", "curly", "long128"}) {
    auto a = groom(name, 48, 1);
    for (const std::string& scene : scene_names()) {
      Simulator sim = make_sim(a);
      SceneGeometry geo = scene_geometry(sim.rest());
      double worst = 0;
      for (uint32_t f = 0; f < 90; ++f) {
        sim.advance(scene_frame(scene, f, geo));
        HealthStats h = health(sim.positions(), sim.rest());
        INFO(name << " " << scene << " frame " << f);
        REQUIRE(h.nan_strands == 0);
        REQUIRE(h.exploded_strands == 0);
        worst = std::max(worst, stretch(sim.positions(), sim.rest()).max);
      }
      INFO(name << " " << scene);
      CHECK(worst < 0.05);
    }
  }
}

TEST_CASE("scenes: settle has no wind or capsules, run has capsules, wind has wind", "[reference][scenes]") {
  SceneGeometry geo;
  geo.head_radius = 0.1;
  TvkSimFrame settle = scene_frame("settle", 3, geo);
  CHECK(settle.capsule_count == 0);
  CHECK(settle.wind.strength == 0.0f);
  CHECK(scene_frame("run", 3, geo).capsule_count == 2);
  CHECK(scene_frame("wind", 3, geo).wind.strength > 0.0f);
  CHECK(scene_frame("teleport", 60, geo).teleport == 1u);
  CHECK(scene_frame("teleport", 61, geo).teleport == 0u);
  CHECK(scene_frame("hitch", 1, geo).dt == 0.25f);
  CHECK_THROWS(scene_frame("nope", 0, geo));
}

TEST_CASE("scenes: the head sphere fitted to the built-in grooms' roots", "[reference][scenes]") {
  auto a = groom("straight", 256);
  SceneGeometry geo = scene_geometry(build_model_rest(a));
  // The built-in grooms grow from a sphere of radius 0.1 m at the origin.
  CHECK(std::abs(geo.head_radius - 0.1) < 1e-4);
  CHECK(length(geo.head_centre) < 1e-4);
}
