// Analytic references on the double-precision reference (docs/accuracy.md lists each with its tolerance and the
// measured value). The same setups run on the GPU in tests/plugin/analytic_test.cpp.
#include <catch2/catch_test_macros.hpp>

#include <cmath>

#include "analytic.hpp"
#include "helpers.hpp"

using namespace tvk_analytic;

TEST_CASE("analytic: the chain's first mode matches the published discrete and continuum periods", "[reference][analytic]") {
  // Values from the analytic notes (discrete: the eigenproblem above; continuum: 4 pi / j0,1 sqrt(L/g)).
  CHECK(std::abs(chain_first_mode(16, 0.3).period - 0.9288) < 5e-4);
  CHECK(std::abs(chain_first_mode(32, 0.3).period - 0.9211) < 5e-4);
  CHECK(std::abs(chain_first_mode(64, 0.3).period - 0.9174) < 5e-4);
  CHECK(std::abs(continuum_chain_period(0.3) - 0.9138) < 5e-4);
  const Catenary c = discrete_catenary(32, 0.3, 0.25);
  CHECK(std::abs(c.sag - 0.0730) < 5e-4);
}

// A1. Tolerances: 1 % at 480 Hz (the highest step rate; the Verlet period error is O((h/T)^2) and the constraint
// projection's O(h) softening is what is left) and 3 % at the default 240 Hz, against the discrete chain of the same
// N (the continuum value is within 0.8 % of it at N = 32 and 0.4 % at N = 64).
// Known to fail on the follow-the-leader length pass (DFTL 0.9): -7.5 % (N 32, 240 Hz), -11 % (480 Hz), -18 % /
// -29 % at N 64. [!shouldfail] until the length constraints are consistent.
TEST_CASE("analytic: a hanging chain swings at its discrete period", "[reference][analytic][!shouldfail]") {
  for (uint32_t n : {32u, 64u}) {
    const double expect = chain_first_mode(n, 0.3).period;
    for (double rate : {240.0, 480.0}) {
      const SwingResult r = swing(reference_factory(), n, rate, 0.0f, 9.0);
      const double err = r.period / expect - 1.0;
      INFO("N " << n << " rate " << rate << " period " << r.period << " expected " << expect << " (continuum "
                << continuum_chain_period(0.3) << ") error " << err);
      CHECK(std::abs(err) <= (rate >= 480.0 ? 0.01 : 0.03));
    }
  }
}

// A2. At zero damping the chain may lose at most 5 % of its amplitude per period (the scheme's numerical
// dissipation); with damping d every step keeps exp(-60 d h) of the velocity, a viscous rate c = 60 d, so the
// amplitude falls by exp(-c T / 2) = exp(-30 d T) per period; within 10 % of that factor's decrement.
// Known to fail on the follow-the-leader length pass: at damping 0 the chain keeps 0.42 of its amplitude per period
// at 240 Hz, 0.65 at 480 Hz. [!shouldfail] until the length constraints are consistent.
TEST_CASE("analytic: damping alone sets the chain's decay", "[reference][analytic][!shouldfail]") {
  for (double rate : {240.0, 480.0}) {
    const SwingResult free = swing(reference_factory(), 32, rate, 0.0f, 9.0);
    INFO("rate " << rate << " amplitude kept per period at damping 0: " << free.amplitude_ratio);
    CHECK(free.amplitude_ratio >= 0.95);
    CHECK(free.amplitude_ratio <= 1.0 + 1e-3);
    const float d = 0.01f;
    const SwingResult damped = swing(reference_factory(), 32, rate, d, 9.0);
    const double expect = std::exp(-30.0 * d * damped.period);
    INFO("damping " << d << ": kept " << damped.amplitude_ratio << " per period, expected " << expect);
    CHECK(std::abs(std::log(damped.amplitude_ratio / free.amplitude_ratio) / std::log(expect) - 1.0) <= 0.1);
  }
}

// A3. The discrete catenary is an equilibrium of the chain pinned at both ends: after 10 s it has not moved by more
// than 1e-3 L, no segment is stretched by more than 1 %, and the sag is within 1 %.
// Known to fail: the final follow-the-leader sweep breaks the segment next to the pinned tip (335 % stretch at
// 240 Hz). [!shouldfail] until that sweep respects a pinned tip.
TEST_CASE("analytic: a strand pinned at both ends hangs as the catenary", "[reference][analytic][!shouldfail]") {
  const Catenary cat = discrete_catenary(32, 0.3, 0.25);
  TvkSimParams p = chain_params();
  p.damping = 0.08f;
  for (double rate : {240.0, 480.0}) {
    auto run = reference_factory()(strand_asset(cat.pts, 1, true), p, settings_at(rate));
    std::vector<Vec3> first;
    for (uint32_t f = 0; f < 600; ++f) {
      run->frame(still_frame());
      if (f == 0) first = run->positions();
    }
    const std::vector<Vec3> last = run->positions();
    double drift = 0, stretch = 0, low = 1e300, top = last.front().y;
    for (size_t i = 0; i < last.size(); ++i) {
      drift = std::max(drift, length(last[i] - first[i]));
      low = std::min(low, last[i].y);
      if (i + 1 < last.size()) {
        const double l0 = length(cat.pts[i + 1] - cat.pts[i]);
        stretch = std::max(stretch, std::abs(length(last[i + 1] - last[i]) / l0 - 1.0));
      }
    }
    const double sag = top - low;
    INFO("rate " << rate << " drift " << drift / 0.3 << " L, stretch " << stretch << ", sag " << sag << " (expected "
                 << cat.sag << ")");
    CHECK(drift <= 1e-3 * 0.3);
    CHECK(stretch <= 0.01);
    CHECK(std::abs(sag / cat.sag - 1.0) <= 0.01);
  }
}

// A6. A straight chain in a steady wind w (no gusts, no cone) tilts by atan(w/g): the wind acts across each segment
// only, so the equilibrium is where gravity + wind lies along the strand. 0.5 degrees, and every vertex within
// 1e-3 L of the straight line (damping settles it; 10 s).
TEST_CASE("analytic: steady wind tilts a hanging strand by atan(w/g)", "[reference][analytic]") {
  std::vector<Vec3> pts;
  for (uint32_t v = 0; v < 32; ++v) pts.push_back({0, -0.3 * v / 31.0, 0});
  TvkSimParams p = chain_params();
  p.damping = 0.3f;
  auto run = reference_factory()(strand_asset(pts, 1), p, settings_at(240.0));
  TvkSimFrame f = still_frame();
  f.wind.direction[0] = 1;
  f.wind.direction[1] = 0;
  f.wind.direction[2] = 0;
  f.wind.strength = 4.0f;
  f.wind.gust_amplitude = 0.0f;
  f.wind.cone_angle = 0.0f;
  for (uint32_t i = 0; i < 600; ++i) run->frame(f);
  const std::vector<Vec3> x = run->positions();
  const Vec3 d = x.back() - x.front();
  const double angle = std::atan2(d.x, -d.y) * 180.0 / std::numbers::pi;
  const double expect = std::atan(4.0 / 9.81) * 180.0 / std::numbers::pi;
  const Vec3 u = normalize(d);
  double off = 0;
  for (const Vec3& v : x) {
    const Vec3 r = v - x.front();
    off = std::max(off, length(r - dot(r, u) * u));
  }
  INFO("tilt " << angle << " deg, expected " << expect << "; off the line " << off / 0.3 << " L");
  CHECK(std::abs(angle - expect) <= 0.5);
  CHECK(off <= 1e-3 * 0.3);
}

// A7. Nothing pinned, VSP off: every vertex falls as Verlet integrates constant gravity from rest, x_n = x_0 +
// g h^2 n (n + 1) / 2 (the continuous x_0 + g t^2 / 2 plus the scheme's constant-velocity offset g h t / 2, which
// comes from starting with p - q = 0), to 1e-9 relative in double; the segments keep their length exactly.
TEST_CASE("analytic: a free strand falls freely", "[reference][analytic]") {
  std::vector<Vec3> pts;
  for (uint32_t v = 0; v < 16; ++v) pts.push_back({0.02 * v, 0.001 * v * v, 0});
  auto run = reference_factory()(strand_asset(pts, 0), chain_params(), settings_at(240.0));
  run->frame(still_frame());  // reset frame: the reset step, then 4 steps
  const std::vector<Vec3> x0 = run->positions();
  uint64_t steps = 4;
  for (uint32_t f = 1; f < 60; ++f) {
    run->frame(still_frame());
    steps += 4;
  }
  const std::vector<Vec3> x = run->positions();
  const double h = 1.0 / 240.0;
  // x0 was taken after 4 steps: the fall between is the difference of the discrete solutions.
  auto fall = [&](uint64_t n) { return 9.81f * h * h * static_cast<double>(n * (n + 1)) / 2.0; };
  const double expect = fall(steps) - fall(4);
  double worst = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    worst = std::max(worst, std::abs((x0[i].y - x[i].y) - expect) / expect);
    worst = std::max(worst, std::abs(x0[i].x - x[i].x) / expect);
  }
  INFO("fell " << x0[0].y - x[0].y << " m, expected " << expect << "; worst relative error " << worst);
  CHECK(worst <= 1e-9);
}
