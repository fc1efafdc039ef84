// Analytic references on the double-precision reference (docs/accuracy.md lists each with its tolerance and the
// measured value). The same setups run on the GPU in tests/plugin/analytic_test.cpp.
#include <catch2/catch_test_macros.hpp>
#include <tressvk/reference/near_duplicates.hpp>

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
// -29 % at N 64. [!shouldfail] while that is the default; the reference's Newmark length model passes it (below).
static void check_chain_period(LengthModel model) {
  for (uint32_t n : {32u, 64u}) {
    const double expect = chain_first_mode(n, 0.3).period;
    for (double rate : {240.0, 480.0}) {
      const SwingResult r = swing(reference_factory(model), n, rate, 0.0f, 9.0);
      const double err = r.period / expect - 1.0;
      INFO("N " << n << " rate " << rate << " period " << r.period << " expected " << expect << " (continuum "
                << continuum_chain_period(0.3) << ") error " << err);
      CHECK(std::abs(err) <= (rate >= 480.0 ? 0.01 : 0.03));
    }
  }
}
TEST_CASE("analytic: a hanging chain swings at its discrete period", "[reference][analytic][!shouldfail]") {
  check_chain_period(LengthModel::kFollowTheLeader);
}
// The Newmark length model (a tridiagonal Newton solve with the transverse response at the average-acceleration state):
// measured +0.01 % at 240 Hz, +0.00 % at 480 Hz for N 32 and 64.
TEST_CASE("analytic: a hanging chain swings at its discrete period (Newmark length model)", "[reference][analytic]") {
  check_chain_period(LengthModel::kNewmark);
}

// A2. At zero damping the chain may lose at most 5 % of its amplitude per period (the scheme's numerical
// dissipation); with damping d every step keeps exp(-60 d h) of the velocity, a viscous rate c = 60 d, so the
// amplitude falls by exp(-c T / 2) = exp(-30 d T) per period; within 10 % of that factor's decrement.
// Known to fail on the follow-the-leader length pass: at damping 0 the chain keeps 0.42 of its amplitude per period
// at 240 Hz, 0.65 at 480 Hz. [!shouldfail] while that is the default; the Newmark length model passes it (below).
static void check_chain_decay(LengthModel model) {
  for (double rate : {240.0, 480.0}) {
    const SwingResult free = swing(reference_factory(model), 32, rate, 0.0f, 9.0);
    INFO("rate " << rate << " amplitude kept per period at damping 0: " << free.amplitude_ratio);
    CHECK(free.amplitude_ratio >= 0.95);
    CHECK(free.amplitude_ratio <= 1.0 + 1e-3);
    const float d = 0.01f;
    const SwingResult damped = swing(reference_factory(model), 32, rate, d, 9.0);
    const double expect = std::exp(-30.0 * d * damped.period);
    INFO("damping " << d << ": kept " << damped.amplitude_ratio << " per period, expected " << expect);
    CHECK(std::abs(std::log(damped.amplitude_ratio / free.amplitude_ratio) / std::log(expect) - 1.0) <= 0.1);
  }
}
TEST_CASE("analytic: damping alone sets the chain's decay", "[reference][analytic][!shouldfail]") {
  check_chain_decay(LengthModel::kFollowTheLeader);
}
// Newmark length model: measured 1.0000 kept per period at damping 0 (240 and 480 Hz).
TEST_CASE("analytic: damping alone sets the chain's decay (Newmark length model)", "[reference][analytic]") {
  check_chain_decay(LengthModel::kNewmark);
}

// The Newmark length model is stable where an explicit transverse response is not (h sqrt(4 T / a) > 2: N 32 at 60
// and 120 Hz, N 64 at 120 Hz, with 1 to 4 Newton steps): the period stays within 3 % and the amplitude within 5 % per
// period at damping 0. Measured: within 0.05 %, >= 0.9986 kept. (N 64 at 60 Hz, h sqrt(4 T / a) about 12, is out of
// this range: -2.1 % with 1 Newton step, noise with more; docs/accuracy.md.)
TEST_CASE("analytic: the Newmark length model is stable at low step rates", "[reference][analytic]") {
  struct Case {
    uint32_t n;
    double rate;
  };
  for (const Case c : {Case{32, 60.0}, Case{32, 120.0}, Case{64, 120.0}}) {
    for (uint32_t li : {1u, 4u}) {
      const SwingResult r = swing(reference_factory(LengthModel::kNewmark), c.n, c.rate, 0.0f, 9.0, 0.3, 0.003, li);
      const double err = r.period / chain_first_mode(c.n, 0.3).period - 1.0;
      INFO("N " << c.n << " rate " << c.rate << " Newton steps " << li << ": period error " << err << ", kept "
                << r.amplitude_ratio);
      CHECK(std::abs(err) <= 0.03);
      CHECK(r.amplitude_ratio >= 0.95);
      CHECK(r.amplitude_ratio <= 1.0 + 1e-3);
    }
  }
}

// p - q is the velocity: a chain settled from its mode with damping keeps no motion in its history. DFTL hands every
// follow-the-leader move back to the parent as velocity, which leaves p - q nonzero in a chain at rest (0.3 m/s
// reported); the Newmark model moves positions only. Largest |p - q| / h over the chain after 20 s at damping 0.5:
// <= 1e-6 m/s (measured: see INFO).
static double settled_speed(LengthModel model) {
  TvkSimParams p = chain_params();
  p.damping = 0.5f;
  tressvk::reference::Simulator sim(strand_asset(chain_in_mode(32, 0.3, 0.003), 1), std::span<const TvkSimParams>(&p, 1),
                                    settings_at(240.0));
  sim.set_length_model(model);
  for (uint32_t f = 0; f < 1200; ++f) sim.advance(still_frame());
  double fastest = 0;
  for (size_t i = 0; i < sim.rest().rest_pos.size(); ++i)
    fastest = std::max(fastest, length(sim.positions()[i] - sim.prev_positions()[i]) * 240.0);
  return fastest;
}
TEST_CASE("analytic: p - q is the velocity of a settled chain (Newmark length model)", "[reference][analytic]") {
  const double v = settled_speed(LengthModel::kNewmark);
  INFO("largest |p - q| / h after 20 s: " << v << " m/s (follow-the-leader: "
                                          << settled_speed(LengthModel::kFollowTheLeader) << " m/s)");
  CHECK(v <= 1e-6);
}

// A3. The discrete catenary is an equilibrium of the chain pinned at both ends: after 10 s it has not moved by more
// than 1e-3 L, no segment is stretched by more than 1 %, and the sag is within 1 %.
// A3. The discrete catenary (N 32, L 0.3 m, supports 0.25 m apart, sag 0.0730 m) is an equilibrium of the chain
// pinned at both ends. Run 10 s from it (damping 0.08 to settle what the scheme moves).
struct CatenaryRun {
  double drift = 0, stretch = 0, sag = 0;
};
static CatenaryRun catenary_run(double rate, LengthModel model = LengthModel::kFollowTheLeader) {
  const Catenary cat = discrete_catenary(32, 0.3, 0.25);
  TvkSimParams p = chain_params();
  p.damping = 0.08f;
  auto run = reference_factory(model)(strand_asset(cat.pts, 1, true), p, settings_at(rate));
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
  for (const LengthModel model : {LengthModel::kFollowTheLeader, LengthModel::kNewmark})
  for (double rate : {240.0, 480.0}) {
    const CatenaryRun r = catenary_run(rate, model);
    INFO((model == LengthModel::kNewmark ? "Newmark" : "follow-the-leader") << " stretch " << r.stretch);
    CHECK(r.stretch <= 0.01);
    INFO("rate " << rate << " drift " << r.drift / 0.3 << " L, sag " << r.sag << " (expected " << cat.sag << ")");
    CHECK(r.drift <= 1e-3 * 0.3);
    CHECK(std::abs(r.sag / cat.sag - 1.0) <= 0.01);
  }
}

// A6. A straight chain in a steady wind w (no gusts, no cone) tilts by atan(w/g): the wind acts across each segment
// only, so the equilibrium is where gravity + wind lies along the strand. 0.5 degrees, and every vertex within
// 1e-3 L of the straight line (damping settles it; 10 s).
TEST_CASE("analytic: steady wind tilts a hanging strand by atan(w/g)", "[reference][analytic]") {
  check_wind_tilt(wind_tilt(reference_factory()));
}

// A7. Nothing pinned, VSP off: every vertex falls as Verlet integrates constant gravity from rest, x_n = x_0 +
// g h^2 n (n + 1) / 2 (the continuous x_0 + g t^2 / 2 plus the scheme's constant-velocity offset g h t / 2, which
// comes from starting with p - q = 0), to 1e-9 relative in double; the segments keep their length exactly.
TEST_CASE("analytic: a free strand falls freely", "[reference][analytic]") {
  check_free_fall(free_fall(reference_factory(), 60), 1e-9);
}

// The converged reference: the same model stepped ever finer (on the CPU, beyond the GPU's 480 Hz) must stop
// changing, or no configuration's model error can be measured against it. Richardson-style halving on the straight
// groom settling as a chain (shape terms off, so every parameter means the same at every step): the distance between
// the trajectories at h and h/2 must shrink by at least 1.5x per halving (first order: 2x).
// Known to fail on the follow-the-leader length pass, whose DFTL velocity correction is a fraction of each step's
// move, not a physical rate: 0.049, 0.049, 0.045, 0.040 (rms / median length) for 240/480 ... 1920/3840 Hz; the same
// in shake, run and wind and on the curly groom (docs/accuracy.md). [!shouldfail] until the length constraints are
// consistent.
// The rms trajectory distance (/ median length) between step rates r and 2r, 240 ... 3840 Hz, `frames` frames.
static std::vector<double> halving_distances(const tressvk::asset::HairAsset& a, const TvkSimParams& p,
                                             const char* scene, uint32_t frames, LengthModel model) {
  double median = 0;
  std::vector<std::vector<std::vector<Vec3>>> runs;
  for (double rate : {240.0, 480.0, 960.0, 1920.0, 3840.0})
    runs.push_back(trajectory(a, p, rate, scene, frames, &median, model));
  std::vector<double> diffs;
  for (size_t k = 0; k + 1 < runs.size(); ++k)
    diffs.push_back(tressvk::reference::trajectory_error(runs[k], runs[k + 1], median).rms_rel);
  return diffs;
}

static void check_convergence(LengthModel model) {
  TvkSimParams p = chain_params();
  p.damping = 0.08f;
  const std::vector<double> diffs = halving_distances(tvk_test::groom("straight", 8), p, "settle", 30, model);
  INFO("rms differences per halving: " << diffs[0] << ", " << diffs[1] << ", " << diffs[2] << ", " << diffs[3]);
  for (size_t k = 0; k + 1 < diffs.size(); ++k) CHECK(diffs[k + 1] * 1.5 <= diffs[k]);
}
TEST_CASE("analytic: the model converges as the step halves (the converged reference exists)",
          "[reference][analytic][!shouldfail]") {
  check_convergence(LengthModel::kFollowTheLeader);
}
// Not yet on the Newmark model either, for another reason: it removes the numerical damping, so the shape-free strands
// whip (the tip of a free chain falling from the rest pose takes the motion up to the step rate) and the halving is
// pre-asymptotic over these rates: 0.35, 0.35, 0.27, 0.16 (rms / median length). The test of convergence for the
// default model needs the shape terms on a consistent footing first (item 2). [!shouldfail] with the numbers.
TEST_CASE("analytic: the model converges as the step halves (Newmark length model)",
          "[reference][analytic][!shouldfail]") {
  check_convergence(LengthModel::kNewmark);
}

// What keeps the Newmark length model from being the default: the local-shape pass (a Gauss-Seidel projection with a
// stiffness fraction per iteration, item 2 of issue 10) adds energy at few iterations, which DFTL's numerical damping
// hid. The curly groom's rest pose without gravity at the defaults (2 local iterations) drifts from rounding level by
// about x1.034 per step under the Newmark model (5e-9 of the median length after 2 s, 0.31 at 1 iteration; stable
// at 4 iterations and with local shape off, and under follow-the-leader). [!shouldfail] until local shape is
// energy-consistent (compliance-based).
TEST_CASE("analytic: the curly rest pose is a fixed point under the Newmark length model", "[reference][analytic][!shouldfail]") {
  const double drift = tvk_test::drift_at_rest(tvk_test::groom("curly", 32, 1), 120, tvk_test::default_params(),
                                               LengthModel::kNewmark);
  INFO("largest drift after 2 s: " << drift << " of the median length");
  CHECK(drift < 1e-12);
}

// ---- SimModel::kCompliant (the lane-parallel model; simulator.hpp, GPU twin shaders/sim/frame_lanes.comp) ---------
// The same analytic checks as above on the compliant model, with the same tolerances.
// Measured: period within +0.01 % (N 32, 64; 240 and 480 Hz); 1.0000 of the amplitude kept per period at damping 0.
TEST_CASE("analytic: a hanging chain swings at its discrete period (compliant model)", "[reference][analytic]") {
  check_chain_period(LengthModel::kCompliant);
}
TEST_CASE("analytic: damping alone sets the chain's decay (compliant model)", "[reference][analytic]") {
  check_chain_decay(LengthModel::kCompliant);
}
TEST_CASE("analytic: p - q is the velocity of a settled chain (compliant model)", "[reference][analytic]") {
  const double v = settled_speed(LengthModel::kCompliant);
  INFO("largest |p - q| / h after 20 s: " << v << " m/s");
  CHECK(v <= 1e-6);
}
TEST_CASE("analytic: a strand pinned at both ends hangs as the catenary (compliant model)", "[reference][analytic]") {
  const Catenary cat = discrete_catenary(32, 0.3, 0.25);
  for (double rate : {240.0, 480.0}) {
    const CatenaryRun r = catenary_run(rate, LengthModel::kCompliant);
    INFO("rate " << rate << " stretch " << r.stretch << " drift " << r.drift / 0.3 << " L, sag " << r.sag
                 << " (expected " << cat.sag << ")");
    CHECK(r.stretch <= 0.01);
    CHECK(r.drift <= 1e-3 * 0.3);
    CHECK(std::abs(r.sag / cat.sag - 1.0) <= 0.01);
  }
}
TEST_CASE("analytic: steady wind and free fall (compliant model)", "[reference][analytic]") {
  const WindTilt t = wind_tilt(reference_factory(LengthModel::kCompliant));
  INFO("tilt " << t.angle_deg << " deg, expected " << t.expected_deg << "; off the line " << t.off_line / 0.3 << " L");
  CHECK(std::abs(t.angle_deg - t.expected_deg) <= 0.5);
  CHECK(t.off_line <= 1e-3 * 0.3);
  const FreeFall f = free_fall(reference_factory(LengthModel::kCompliant), 60);
  INFO("fell " << f.fell << " m, expected " << f.expected << "; worst relative error " << f.worst);
  CHECK(f.worst <= 1e-9);
}
// The shape-free straight chain whips (its tip takes the motion up to the step rate) and its halving is pre-asymptotic
// over these rates, as on the Newmark model: 0.013, 0.011, 0.021, 0.019. [!shouldfail] with the numbers.
TEST_CASE("analytic: the model converges as the step halves (compliant model, shape-free chain)",
          "[reference][analytic][!shouldfail]") {
  check_convergence(LengthModel::kCompliant);
}
// With the shape terms on (the curly groom shaken at the defaults) the compliant model should converge: the rms
// distance between the trajectories at r and 2r (240 ... 3840 Hz, 30 frames) falling every halving and by at least 5x
// over the four (first order would be 16x). It did (1.5e-3, 7.2e-4, 3.0e-4, 2.0e-4: 7.5x) while the shape constraints'
// 0.1 s damping acted on each edge's whole change over the step: that damping also dragged the edges' rigid turns,
// which made strands standing up from the crown creep without settling and amplify float rounding by 1e5 in a second
// (docs/accuracy.md, "Rounding amplification"). With 5 ms (and local targets) nothing creeps and rounding stays at
// its level, but the curly groom's bending waves are nearly undamped and the halving does not converge over these
// rates: 0.014, 0.026, 0.026, 0.041 of the median length. An internal damping of the constraints' own change
// (20 ms) converges (2.1e-3, 1.2e-3, 5.6e-4, 3.2e-4) but biases the static sag at 1-2 iterations (cantilever +15 %
// at 1 iteration), because the targets are held from the predicted state. [!shouldfail] until a damping that is
// both unbiased and internal exists.
TEST_CASE("analytic: the curly groom's shaken trajectory converges as the step halves (compliant model)",
          "[reference][analytic][!shouldfail]") {
  const std::vector<double> diffs =
      halving_distances(tvk_test::groom("curly", 8), tvk_test::default_params(), "shake", 30, LengthModel::kCompliant);
  INFO("rms differences per halving: " << diffs[0] << ", " << diffs[1] << ", " << diffs[2] << ", " << diffs[3]);
  for (size_t k = 0; k + 1 < diffs.size(); ++k) CHECK(diffs[k + 1] < diffs[k]);
  CHECK(diffs.back() * 5.0 <= diffs.front());
}

// Rounding amplification (docs/accuracy.md): the same scene twice on the double reference, the second with every free
// vertex moved by `eps` of the median length in a pseudo-random direction after the first frame; the largest distance
// between the two at the end (/ median length). Float rounding on the GPU is such a perturbation every step.
namespace {
double perturbed_apart(const tressvk::asset::HairAsset& a, const char* scene, uint32_t frames, double eps,
                       LengthModel model = LengthModel::kCompliant) {
  const TvkSimParams p = tvk_test::default_params();
  tressvk::reference::Simulator sa = tvk_test::make_sim(a, p), sb = tvk_test::make_sim(a, p);
  sa.set_model(model);
  sb.set_model(model);
  const auto geo = tressvk::reference::scene_geometry(sa.rest());
  sa.advance(tressvk::reference::scene_frame(scene, 0, geo));
  sb.advance(tressvk::reference::scene_frame(scene, 0, geo));
  uint64_t seed = 12345;
  auto rnd = [&] {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(seed >> 11) / 9007199254740992.0 * 2.0 - 1.0;
  };
  const size_t count = sa.rest().rest_pos.size();
  auto pos = sb.mutable_positions();
  for (size_t i = 0; i < count; ++i) {
    if (sb.rest().inv_mass[i] > 0.0) pos[i] += eps * sa.median_strand_length() * Vec3{rnd(), rnd(), rnd()};
  }
  for (uint32_t f = 1; f <= frames; ++f) {
    sa.advance(tressvk::reference::scene_frame(scene, f, geo));
    sb.advance(tressvk::reference::scene_frame(scene, f, geo));
  }
  return tvk_test::max_rel(sa.positions().first(count), sb.positions().first(count), sa.median_strand_length());
}
}  // namespace

// The straight groom's strands near the crown stand up, under compression by their own weight. With the shape
// targets taken from a frame transported along the whole strand and a 0.1 s damping of each edge's whole change they
// crept without settling, and a 1e-7 perturbation grew to 3.0e-2 of the median length in one second of `shake` (the
// hard cases' 10 km and 1/100 / 100x failures: 3 % of the length from the reference). Now: 1.0e-7 (it does not grow).
// The bar, 1e-5, is 100x the perturbation: float rounding (5e-7 per frame) must stay far under the hard cases' 1e-4.
TEST_CASE("analytic: the compliant model does not amplify rounding on upright strands (straight groom, shake)",
          "[reference][analytic]") {
  const double apart = perturbed_apart(tvk_test::groom("straight", 16), "shake", 60, 1e-7);
  INFO("1e-7 perturbation after 60 frames of shake: " << apart);
  CHECK(apart <= 1e-5);
}

// One straight strand (L 0.15 m, 2 root vertices pinned, defaults) standing 76 degrees above the horizontal falls over
// and settles: before, it crept at 5 cm/s for ever (a 1e-12 perturbation grew to 7.6e-2 L in 5 s); now it is still
// to 1e-11 m/s after 5 s and the perturbation has decayed (measured 3.6e-14 L).
TEST_CASE("analytic: an upright strand falls over and settles (compliant model)", "[reference][analytic]") {
  std::vector<Vec3> pts;
  const double angle = 76.0 * 3.14159265358979 / 180.0;
  for (uint32_t v = 0; v < 32; ++v) pts.push_back({0.15 * v / 31 * std::cos(angle), 0.15 * v / 31 * std::sin(angle), 0});
  const auto a = strand_asset(pts, 2);
  const TvkSimParams p = tvk_test::default_params();
  ReferenceRun ra(a, p, settings_at(240.0), LengthModel::kCompliant), rb(a, p, settings_at(240.0), LengthModel::kCompliant);
  ra.frame(still_frame());
  rb.frame(still_frame());
  auto pos = rb.sim().mutable_positions();
  for (uint32_t v = 2; v < 32; ++v) pos[v] += 0.15e-12 * Vec3{std::sin(v * 1.7), std::cos(v * 2.3), std::sin(v * 0.9)};
  for (uint32_t f = 1; f <= 300; ++f) {
    ra.frame(still_frame());
    rb.frame(still_frame());
  }
  const auto xa = ra.sim().positions(), xb = rb.sim().positions(), qa = ra.sim().prev_positions();
  double apart = 0, speed = 0;
  for (uint32_t v = 0; v < 32; ++v) {
    apart = std::max(apart, length(xa[v] - xb[v]) / 0.15);
    speed = std::max(speed, length(xa[v] - qa[v]) * 240.0);
  }
  INFO("after 5 s: fastest vertex " << speed << " m/s, 1e-12 perturbation now " << apart);
  CHECK(speed <= 1e-6);
  CHECK(apart <= 1e-9);
}

// Hard case 8 on the reference: the straight groom with sub-micrometre segments (in guide 0 vertex 5 0.2 um after
// vertex 4, in guide 1 the tip 0.2 um after vertex N-2, in guide 2 vertices 8-10 within 0.4 um of vertex 7; as
// tressvk-bench hardcases builds it), 60 frames of shake. The damped Newton step measured its reach against the
// shortest segment, so one 0.1 um segment held every step of its strand to 0.05 um and the strand's other segments
// stayed stretched by up to 75 %; then the reach was measured against segments of at least half the mean segment:
// worst 4.4e-3. Now such strands are respaced evenly on load (model::kRespaceBelowRel; the rounding those segments
// amplified is gone too, docs/accuracy.md "Hard cases"): worst 1.0e-3, the length solve's tolerance. The bar is the
// hard cases' 5 %.
namespace {
// The worst stretch (reference::stretch) of the groom on the compliant model over `frames` frames of `scene`.
double compliant_worst_stretch(const tressvk::asset::HairAsset& a, const char* scene, uint32_t frames) {
  tressvk::reference::Simulator sim = tvk_test::make_sim(a);
  sim.set_model(LengthModel::kCompliant);
  const auto geo = tressvk::reference::scene_geometry(sim.rest());
  double worst = 0;
  for (uint32_t f = 0; f < frames; ++f) {
    sim.advance(tressvk::reference::scene_frame(scene, f, geo));
    worst = std::max(worst, tressvk::reference::stretch(sim.positions().first(sim.rest().rest_pos.size()), sim.rest()).max);
  }
  return worst;
}
}  // namespace

TEST_CASE("analytic: the compliant length solve holds strands with sub-micrometre segments", "[reference][analytic]") {
  const auto a = tressvk::reference::with_near_duplicate_vertices(tvk_test::groom("straight", 8));
  const double worst = compliant_worst_stretch(a, "shake", 60);
  INFO("worst stretch over 60 frames of shake: " << worst);
  CHECK(worst <= 0.05);
}

// The curly groom at rest keeps its strands at their length at any vertex count. With one shape-damping time for every
// edge (5 ms, what lets upright strands settle and keeps rounding at its level at N 32) strands of more than 32
// vertices fluttered and stretched: the worst segment 0.17 off its length at N 40, 0.71 at N 64, after 120 frames at
// rest (hard case 3, tight curls at 64 vertices, failed the same way). The damping time now grows as the edge's
// length shrinks, (31 a / L)^-2, up to 4x (20 ms at N 64 and above): on this reference 3.0e-5 at N 16, 2.1e-8 at
// N 48, 5.8e-11 at N 64 and 5.3e-11 at N 128 (the GPU on lavapipe: 1.3e-6 at N 64; before: 0.55 / 0.68 / 0.49 at N
// 48 / 64 / 128). The bar is the length solve's stopping tolerance, 1e-3 (kCompliantStretchTol): a strand at rest
// under gravity is never past it.
TEST_CASE("analytic: the curly groom at rest keeps its length at 16 to 128 vertices (compliant model)",
          "[reference][analytic]") {
  for (uint32_t n : {16u, 48u, 64u, 128u}) {
    const double worst = compliant_worst_stretch(tvk_test::groom("curly", 8, 0, n), "settle", 120);
    INFO("N " << n << ": worst stretch over 120 frames at rest " << worst);
    CHECK(worst <= 1e-3);
  }
}

namespace {
// The cantilever's sag over the grid around N 32, 240 Hz, 2 iterations: each within 10 % of it (rates under 100 Hz
// within tol_low_rate).
void check_cantilever_grid(LengthModel model, double tol_low_rate) {
  const RunFactory make = reference_factory(model);
  const double base = cantilever_sag(make, 32, 240.0, 2);
  INFO("sag at N 32, 240 Hz, 2 iterations: " << base * 1e3 << " mm");
  CHECK(base > 0.01);
  for (uint32_t n : {16u, 64u, 128u}) {
    const double s = cantilever_sag(make, n, 240.0, 2);
    INFO("N " << n << ": " << s * 1e3 << " mm");
    CHECK(std::abs(s / base - 1.0) <= 0.10);
  }
  for (double rate : {60.0, 120.0, 480.0}) {
    const double s = cantilever_sag(make, 32, rate, 2);
    INFO("rate " << rate << ": " << s * 1e3 << " mm");
    CHECK(std::abs(s / base - 1.0) <= (rate < 100.0 ? tol_low_rate : 0.10));
  }
  for (uint32_t it : {1u, 4u, 8u}) {
    const double s = cantilever_sag(make, 32, 240.0, it);
    INFO("iterations " << it << ": " << s * 1e3 << " mm");
    CHECK(std::abs(s / base - 1.0) <= 0.10);
  }
}
}  // namespace

// A8. The cantilever's sag does not depend on N, step rate or iteration count: within 10 % of its value at N 32,
// 240 Hz, 2 iterations (94.3 mm) over N {16, 32, 64, 128}, rates {120, 240, 480} Hz and iterations {1, 2, 4, 8}.
// 60 Hz is checked at 20 %: measured +12.7 % there (the global shape spring pulls before the shape solve and outside
// it: the conservative model's test below weighs the vertices it pulls and is within 10 %); elsewhere at most +4.8 %
// (120 Hz). The follow-the-leader model spreads over 28-174 mm (6x) on the same grid (TVK_DAMP=0.5
// tressvk_accuracy_probe cantilever).
TEST_CASE("analytic: a cantilever's sag is independent of N, step rate and iterations (compliant model)",
          "[reference][analytic]") {
  check_cantilever_grid(LengthModel::kCompliant, 0.20);
}

// The curly rest pose without gravity is a fixed point (what kept the Newmark length model from the default: the
// Gauss-Seidel local shape gained energy under it), at 1 and 2 local iterations.
namespace {
void check_curly_rest_fixed_point(LengthModel model) {
  for (uint32_t it : {1u, 2u}) {
    TvkSimParams p = tvk_test::default_params();
    p.local_iterations = it;
    const double drift = tvk_test::drift_at_rest(tvk_test::groom("curly", 32, 1), 120, p, model);
    INFO(it << " iterations: largest drift after 2 s: " << drift << " of the median length");
    CHECK(drift < 1e-12);
  }
}
}  // namespace

TEST_CASE("analytic: the curly rest pose is a fixed point (compliant model)", "[reference][analytic]") {
  check_curly_rest_fixed_point(LengthModel::kCompliant);
}

// ---- The conservative local shape (LengthModel::kConservative; docs/accuracy.md) --------------------------------
// kCompliant holds each shape target while it solves, so the target's dependence on the edge before it has no reaction
// and the shape force is not the gradient of an energy: the curly groom's trajectory stops converging as h shrinks
// (above). kConservative solves the same constraints with their full gradient (a banded block system).

// The curly groom shaken at the defaults converges as the step halves: the rms distance between the trajectories at r
// and 2r (240 ... 3840 Hz, 30 frames) falls every halving and stays at the 1e-4 level of the median length (measured
// 1.8e-4, 1.3e-4, 9.8e-5, 7.7e-5; kCompliant: 1.4e-2, 2.6e-2, 2.6e-2, 4.1e-2). The distances fall by 2.4x over the
// four halvings, not the 5x the straight groom shows below: from 240 Hz on they are already at 1e-4 of the length, set
// by bending waves that the 1.5 ms damping takes out slowly; the bar on each is 3e-4 (1.7x the largest).
// Over 60-3840 Hz and 120 frames (tressvk_accuracy_probe convergence): 7.2e-4 ... 5.0e-5, 14x.
TEST_CASE("analytic: the curly groom's shaken trajectory converges as the step halves (conservative local shape)",
          "[reference][analytic]") {
  const std::vector<double> diffs =
      halving_distances(tvk_test::groom("curly", 8), tvk_test::default_params(), "shake", 30, LengthModel::kConservative);
  INFO("rms differences per halving: " << diffs[0] << ", " << diffs[1] << ", " << diffs[2] << ", " << diffs[3]);
  for (size_t k = 0; k + 1 < diffs.size(); ++k) CHECK(diffs[k + 1] < diffs[k]);
  for (double d : diffs) CHECK(d <= 3e-4);
}

// The straight groom (8 long strands swinging down from upright and horizontal) converges too: 240 ... 3840 Hz,
// settle: 2.7e-2, 7.5e-3, 1.8e-3, 5.3e-4 (50x; kCompliant 4.8e-3 ... 8.4e-3, not converging); shake: 6.7e-2, 3.1e-2,
// 1.1e-2, 1.4e-3 (46x). The bar: falling every halving and 5x over the four.
TEST_CASE("analytic: the straight groom's trajectory converges as the step halves (conservative local shape)",
          "[reference][analytic]") {
  const auto a = tvk_test::groom("straight", 8);
  for (const char* scene : {"settle", "shake"}) {
    const std::vector<double> diffs =
        halving_distances(a, tvk_test::default_params(), scene, 30, LengthModel::kConservative);
    INFO(scene << ": rms differences per halving: " << diffs[0] << ", " << diffs[1] << ", " << diffs[2] << ", "
               << diffs[3]);
    for (size_t k = 0; k + 1 < diffs.size(); ++k) CHECK(diffs[k + 1] < diffs[k]);
    CHECK(diffs.back() * 5.0 <= diffs.front());
  }
}

// Hard case 2's strands (long128 8 x 128, run) at 120 Hz with 1 local iteration: the capsules push vertices further
// in a step than the compliant length solve's damped Newton steps restore, and before the conservative model's length
// fallback (a follow-the-leader clean-up weighted by how far over 4e-3 the worst segment is) a segment reached 0.41
// of its length (16 extra Newton steps instead of 4: 0.35). Measured with it 3.9e-3; the bar is 0.01, the hard
// cases' 0.05 (at the default settings the worst is 1e-3, the Newton steps' own tolerance).
TEST_CASE("analytic: the conservative model keeps 128-vertex strands' lengths in collisions at 120 Hz and 1 iteration",
          "[reference][analytic]") {
  const auto a = tvk_test::groom("long128", 8, 0, 128);
  TvkSimParams p = tvk_test::default_params();
  p.local_iterations = 1;
  TvkSimSettings s = tvk_test::default_settings();
  s.time.step_rate = 120.0f;
  tressvk::reference::Simulator sim = tvk_test::make_sim(a, p, s);
  sim.set_model(LengthModel::kConservative);
  const auto geo = tressvk::reference::scene_geometry(sim.rest());
  double worst = 0.0;
  for (uint32_t f = 0; f < 60; ++f) {
    sim.advance(tressvk::reference::scene_frame("run", f, geo));
    worst = std::max(worst,
                     tressvk::reference::stretch(sim.positions().first(sim.rest().rest_pos.size()), sim.rest()).max);
  }
  INFO("worst stretch " << worst);
  CHECK(worst <= 0.01);
}

// A8 on the conservative local shape: within 10 % of its value at N 32, 240 Hz, 2 iterations over the whole grid,
// 60 Hz included (kCompliant: +12.7 % there). Measured 88.6-99.7 mm around 94.3 (-6.1 % at 120 Hz, +5.7 % at N 16, 60 Hz
// -1.2 %). 60 Hz needed the global shape spring inside the step's implicit solve: the local shape solve weighs a vertex
// the spring pulls by 1 / (1 + k h^2) (without: +16.6 % at 60 Hz).
TEST_CASE("analytic: a cantilever's sag is independent of N, step rate and iterations (conservative local shape)",
          "[reference][analytic]") {
  check_cantilever_grid(LengthModel::kConservative, 0.10);
}


// A conservative shape force takes energy out of a perturbation instead of putting it in: the curly groom shaken for
// 60 frames with a 1e-7 perturbation ends 2e-16 apart (kCompliant: 6.4e-7, growing), and the straight groom's upright
// strands do not amplify it (measured 1.1e-7). The bars are kCompliant's test above (1e-5) and 1e-7 for the curly groom.
TEST_CASE("analytic: the conservative local shape does not amplify rounding", "[reference][analytic]") {
  const double straight = perturbed_apart(tvk_test::groom("straight", 16), "shake", 60, 1e-7, LengthModel::kConservative);
  const double curly = perturbed_apart(tvk_test::groom("curly", 16), "shake", 60, 1e-7, LengthModel::kConservative);
  INFO("1e-7 perturbation after 60 frames of shake: straight " << straight << ", curly " << curly);
  CHECK(straight <= 1e-5);
  CHECK(curly <= 1e-7);
}

TEST_CASE("analytic: the curly rest pose is a fixed point (conservative local shape)", "[reference][analytic]") {
  check_curly_rest_fixed_point(LengthModel::kConservative);
}
