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
// A3. The discrete catenary (N 32, L 0.3 m, supports 0.25 m apart, sag 0.0730 m) is an equilibrium of the chain
// pinned at both ends. Run 10 s from it (damping 0.08 to settle what the scheme moves).
struct CatenaryRun {
  double drift = 0, stretch = 0, sag = 0;
};
static CatenaryRun catenary_run(double rate) {
  const Catenary cat = discrete_catenary(32, 0.3, 0.25);
  TvkSimParams p = chain_params();
  p.damping = 0.08f;
  auto run = reference_factory()(strand_asset(cat.pts, 1, true), p, settings_at(rate));
  std::vector<Vec3> first, last;
  CatenaryRun r;
  for (uint32_t f = 0; f < 600; ++f) {
    run->frame(still_frame());
    last = run->positions();
    if (f == 0) first = last;
    for (size_t i = 0; i + 1 < last.size(); ++i) {  // every frame: the worst moment counts
      const double l0 = length(cat.pts[i + 1] - cat.pts[i]);
      r.stretch = std::max(r.stretch, std::abs(length(last[i + 1] - last[i]) / l0 - 1.0));
    }
  }
  double low = 1e300;
  for (size_t i = 0; i < last.size(); ++i) {
    r.drift = std::max(r.drift, length(last[i] - first[i]));
    low = std::min(low, last[i].y);
  }
  r.sag = last.front().y - low;
  return r;
}

// Stretch <= 1 % in every frame: every segment, including the one next to the pinned tip, at its length. With the
// root-to-tip follow-the-leader sweep that segment ended 335 % stretched (240 Hz); followed from both ends, the
// segments beside the middle reached 170 % while the halves slid.
TEST_CASE("analytic: a strand pinned at both ends keeps its segment lengths", "[reference][analytic]") {
  for (double rate : {240.0, 480.0}) {
    const CatenaryRun r = catenary_run(rate);
    INFO("rate " << rate << " stretch " << r.stretch);
    CHECK(r.stretch <= 0.01);
  }
}

// Drift <= 1e-3 L and sag within 1 % of the catenary's: the catenary is the balance of forces, which the consistent
// solve of a tip-pinned strand reproduces (follow-the-leader's fixed point was 12 % short of it, drift 0.13 L).
TEST_CASE("analytic: a strand pinned at both ends hangs as the catenary", "[reference][analytic]") {
  const Catenary cat = discrete_catenary(32, 0.3, 0.25);
  for (double rate : {240.0, 480.0}) {
    const CatenaryRun r = catenary_run(rate);
    INFO("rate " << rate << " drift " << r.drift / 0.3 << " L, sag " << r.sag << " (expected " << cat.sag << ")");
    CHECK(r.drift <= 1e-3 * 0.3);
    CHECK(std::abs(r.sag / cat.sag - 1.0) <= 0.01);
  }
}

// A6. A straight chain in a steady wind w (no gusts, no cone) tilts by atan(w/g): the wind acts across each segment
// only, so the equilibrium is where gravity + wind lies along the strand. 0.5 degrees, and every vertex within
// 1e-3 L of the straight line (damping settles it; 10 s).
TEST_CASE("analytic: steady wind tilts a hanging strand by atan(w/g)", "[reference][analytic]") {
  const WindTilt t = wind_tilt(reference_factory());
  INFO("tilt " << t.angle_deg << " deg, expected " << t.expected_deg << "; off the line " << t.off_line / 0.3 << " L");
  CHECK(std::abs(t.angle_deg - t.expected_deg) <= 0.5);
  CHECK(t.off_line <= 1e-3 * 0.3);
}

// A7. Nothing pinned, VSP off: every vertex falls as Verlet integrates constant gravity from rest, x_n = x_0 +
// g h^2 n (n + 1) / 2 (the continuous x_0 + g t^2 / 2 plus the scheme's constant-velocity offset g h t / 2, which
// comes from starting with p - q = 0), to 1e-9 relative in double; the segments keep their length exactly.
TEST_CASE("analytic: a free strand falls freely", "[reference][analytic]") {
  const FreeFall f = free_fall(reference_factory(), 60);
  INFO("fell " << f.fell << " m, expected " << f.expected << "; worst relative error " << f.worst);
  CHECK(f.worst <= 1e-9);
}

// The converged reference: the same model stepped ever finer (on the CPU, beyond the GPU's 480 Hz) must stop
// changing, or no configuration's model error can be measured against it. Richardson-style halving on the straight
// groom settling as a chain (shape terms off, so every parameter means the same at every step): the distance between
// the trajectories at h and h/2 must shrink by at least 1.5x per halving (first order: 2x).
// Known to fail on the follow-the-leader length pass, whose DFTL velocity correction is a fraction of each step's
// move, not a physical rate: 0.049, 0.049, 0.045, 0.040 (rms / median length) for 240/480 ... 1920/3840 Hz; the same
// in shake, run and wind and on the curly groom (docs/accuracy.md). [!shouldfail] until the length constraints are
// consistent.
TEST_CASE("analytic: the model converges as the step halves (the converged reference exists)",
          "[reference][analytic][!shouldfail]") {
  TvkSimParams p = chain_params();
  p.damping = 0.08f;
  const auto a = tvk_test::groom("straight", 8);
  double median = 0;
  std::vector<std::vector<std::vector<Vec3>>> runs;
  for (double rate : {240.0, 480.0, 960.0, 1920.0, 3840.0}) runs.push_back(trajectory(a, p, rate, "settle", 30, &median));
  std::vector<double> diffs;
  for (size_t k = 0; k + 1 < runs.size(); ++k) {
    diffs.push_back(tressvk::reference::trajectory_error(runs[k], runs[k + 1], median).rms_rel);
  }
  INFO("rms differences per halving: " << diffs[0] << ", " << diffs[1] << ", " << diffs[2] << ", " << diffs[3]);
  for (size_t k = 0; k + 1 < diffs.size(); ++k) CHECK(diffs[k + 1] * 1.5 <= diffs[k]);
}
