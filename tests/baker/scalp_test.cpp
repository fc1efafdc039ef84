// Root orientation against a scalp: the triangle grid must agree with brute force everywhere, near and far.
#include "test_support.hpp"

#include <catch2/catch_approx.hpp>

#include <cmath>

using namespace tressvk;
using Catch::Approx;

namespace {

// A bumpy sphere cap of radius 0.1 (a scalp), n x n quads split into triangles.
baker::ScalpMesh cap(int n) {
  baker::ScalpMesh m;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double th = 1.4 * i / n, ph = 6.283185307179586 * j / n;
      const double r = 0.1 * (1 + 0.05 * std::sin(5 * ph) * std::sin(3 * th));
      m.vertices.push_back({r * std::sin(th) * std::cos(ph), r * std::cos(th), r * std::sin(th) * std::sin(ph)});
    }
  auto id = [&](int i, int j) { return static_cast<uint32_t>(i * (n + 1) + j); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

void compare(const baker::ScalpMesh& m, double extent, uint64_t seed) {
  uint64_t state = seed;
  auto uniform = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  };
  for (int k = 0; k < 300; ++k) {
    // Points near the surface, inside, and far outside the mesh's bounds.
    const double spread = k < 100 ? 1.2 : k < 200 ? 0.5 : 6.0;
    const baker::Vec3 p{(uniform() - 0.5) * 2 * extent * spread, (uniform() - 0.5) * 2 * extent * spread,
                        (uniform() - 0.5) * 2 * extent * spread};
    // Both compute the same minimum over the same triangle distances: equal up to rounding of sqrt.
    CHECK(baker::distance_to_scalp(p, m) == Approx(baker::distance_to_scalp_brute_force(p, m)).epsilon(1e-12));
  }
}

}  // namespace

TEST_CASE("Scalp distance: grid search equals brute force", "[baker][scalp]") {
  compare(cap(40), 0.1, 1);
  compare(cap(3), 0.1, 2);  // coarse mesh, few cells
  baker::ScalpMesh flat;   // a single flat triangle: a degenerate (zero-thickness) grid
  flat.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  flat.triangles = {{0, 1, 2}};
  compare(flat, 1.0, 3);
}

TEST_CASE("Scalp orientation: the grid's early-stopping comparison agrees with brute force", "[baker][scalp]") {
  const auto m = cap(30);
  uint64_t state = 7;
  auto uniform = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  };
  baker::RawGroom g;
  g.group_names = {"g"};
  for (int k = 0; k < 400; ++k) {
    // Two-point strands with ends near the cap, inside it and far away, in random order.
    const double s1 = k % 3 == 0 ? 0.15 : 0.6, s2 = k % 5 == 0 ? 3.0 : 0.25;
    const baker::Vec3 ends[2] = {{(uniform() - 0.5) * s1, (uniform() - 0.5) * s1 + 0.1, (uniform() - 0.5) * s1},
                                 {(uniform() - 0.5) * s2, (uniform() - 0.5) * s2, (uniform() - 0.5) * s2}};
    g.add_strand(ends, 2, 0);
  }
  auto oriented = g;
  baker::orient_to_scalp(oriented, m);
  for (size_t k = 0; k < g.strand_count(); ++k) {
    const auto a = g.points[2 * k], b = g.points[2 * k + 1];
    const bool flip = baker::distance_to_scalp_brute_force(b, m) < baker::distance_to_scalp_brute_force(a, m);
    CHECK(oriented.points[2 * k] == (flip ? b : a));
  }
}

TEST_CASE("Scalp distance on the Sintel character mesh", "[baker][scalp][data]") {
  TVK_REQUIRE_DATA(dir);
  const auto mesh = baker::load_scalp(dir / "sintel" / "sintel.obj");
  REQUIRE(mesh.triangles.size() >= 5952);
  compare(mesh, 30.0, 4);
}
