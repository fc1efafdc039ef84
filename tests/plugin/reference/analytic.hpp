// Analytic references for the strand model (docs/accuracy.md): single-strand setups whose motion is known in
// closed form or from a small exact computation, shared by the reference's CPU tests and the GPU tests. A setup
// is run through a StrandRun (the double reference or a GPU instance) so both sides meet the same numbers.
//
// Mass model: every free vertex has unit mass (the model ignores inverse masses other than 0 / non-zero), so the
// discrete chain below is exactly the system the simulator approximates.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <catch2/catch_test_macros.hpp>

#include <tressvk/asset.hpp>
#include <tressvk/baker/bake.hpp>
#include <tressvk/model/math.hpp>
#include <tressvk/reference/converged.hpp>
#include <tressvk/reference/metrics.hpp>
#include <tressvk/reference/scenes.hpp>
#include <tressvk/reference/simulator.hpp>

namespace tvk_analytic {

using tressvk::reference::Vec3;

inline constexpr double kG = 9.81;

// One strand from a polyline (metres, root first), baked with `pin` root vertices held (and as many at the tip
// when pin_tip). The baker's arc-length resampling keeps an equally spaced polyline of N points as it is.
inline tressvk::asset::HairAsset strand_asset(const std::vector<Vec3>& pts, uint32_t pin, bool pin_tip = false) {
  tressvk::baker::RawGroom raw;
  raw.group_names = {"strand"};
  std::vector<tressvk::baker::Vec3> p;
  for (const Vec3& v : pts) p.push_back({v.x, v.y, v.z});
  raw.add_strand(p.data(), p.size(), 0, pin_tip);
  raw.input_vertices = p.size();
  tressvk::baker::BakeOptions o;
  o.vertices_per_strand = static_cast<uint32_t>(pts.size());
  o.pin = pin;
  o.shuffle = false;
  o.merge_fraction = 1e-9;
  tressvk::asset::HairAsset a = tressvk::baker::bake(raw, o);
  // Free fall: pin 0 leaves every vertex free.
  return a;
}

// Parameters with every shape term, damping, VSP and the speed clamp off: a pure inextensible chain.
inline TvkSimParams chain_params() {
  TvkSimParams p = TVK_SIM_PARAMS_DEFAULT_INIT;
  p.damping = 0.0f;
  p.global_stiffness = 0.0f;
  p.local_stiffness = 0.0f;
  p.local_iterations = 0;
  p.vsp_coefficient = 0.0f;
  p.max_speed = 0.0f;
  p.length_iterations = 1;
  return p;
}

inline TvkSimSettings settings_at(double rate) {
  TvkSimSettings s = TVK_SIM_SETTINGS_DEFAULT_INIT;
  s.time.step_rate = static_cast<float>(rate);
  return s;
}

inline TvkSimFrame still_frame(double dt = 1.0 / 60.0) {
  TvkSimFrame f{};
  f.dt = static_cast<float>(dt);
  f.transform = TVK_INSTANCE_TRANSFORM_DEFAULT_INIT;
  f.wind = TVK_WIND_DEFAULT_INIT;
  return f;
}

// ---- A1: the hanging chain ------------------------------------------------------------------------------------
// N vertices, vertex 0 pinned, segment a = L/(N-1), unit mass per free vertex. Segment j (vertices j, j+1) carries
// the weight of the N-1-j free vertices below it: T_j = g (N-1-j). Small transverse swings x_1..x_{N-1} obey
// x'' = -K x with K_ii = (T_{i-1} + T_i)/a, K_{i,i+1} = K_{i+1,i} = -T_i/a (T_{N-1} = 0).
struct ChainMode {
  double period = 0;          // 2 pi / sqrt(lambda_min), s
  std::vector<double> shape;  // x_0..x_{N-1}, x_0 = 0, tip = 1
};

inline ChainMode chain_first_mode(uint32_t n, double length, double g = kG) {
  const uint32_t m = n - 1;  // free vertices 1..n-1 -> index 0..m-1
  const double a = length / static_cast<double>(m);
  auto tension = [&](uint32_t seg) { return seg + 1 < n ? g * static_cast<double>(n - 1 - seg) : 0.0; };
  std::vector<double> diag(m), off(m, 0.0);  // off[k] couples k and k+1
  for (uint32_t k = 0; k < m; ++k) {
    const uint32_t i = k + 1;
    diag[k] = (tension(i - 1) + tension(i)) / a;
    if (k + 1 < m) off[k] = -tension(i) / a;
  }
  // Inverse iteration (K is symmetric positive definite and tridiagonal): x <- K^-1 x converges to the mode of the
  // smallest eigenvalue.
  std::vector<double> x(m, 1.0), y(m);
  double lambda = 0;
  for (int it = 0; it < 200; ++it) {
    // Thomas algorithm for K y = x.
    std::vector<double> c(m), d(m);
    c[0] = off[0] / diag[0];
    d[0] = x[0] / diag[0];
    for (uint32_t k = 1; k < m; ++k) {
      const double den = diag[k] - off[k - 1] * c[k - 1];
      c[k] = k + 1 < m ? off[k] / den : 0.0;
      d[k] = (x[k] - off[k - 1] * d[k - 1]) / den;
    }
    y[m - 1] = d[m - 1];
    for (uint32_t k = m - 1; k-- > 0;) y[k] = d[k] - c[k] * y[k + 1];
    double xy = 0, yy = 0;
    for (uint32_t k = 0; k < m; ++k) {
      xy += x[k] * y[k];
      yy += y[k] * y[k];
    }
    lambda = xy / yy;  // Rayleigh quotient of K at y: (y.Ky)/(y.y) = (y.x)/(y.y)
    const double nrm = std::sqrt(yy);
    for (uint32_t k = 0; k < m; ++k) x[k] = y[k] / nrm;
  }
  ChainMode mode;
  mode.period = 2.0 * std::numbers::pi / std::sqrt(lambda);
  mode.shape.assign(n, 0.0);
  for (uint32_t k = 0; k < m; ++k) mode.shape[k + 1] = x[k] / x[m - 1];
  return mode;
}

// The continuum hanging chain: 4 pi / j0,1 sqrt(L/g), j0,1 = 2.404825557695773.
inline double continuum_chain_period(double length, double g = kG) {
  return 4.0 * std::numbers::pi / 2.404825557695773 * std::sqrt(length / g);
}

// The chain displaced into its first mode (tip amplitude `amp` along +x), every segment of length a, hanging from
// the origin along -y. Baked as the rest pose: with shape terms off the rest pose only fixes the lengths, so the
// reset frame starts the chain displaced and at rest.
inline std::vector<Vec3> chain_in_mode(uint32_t n, double length, double amp) {
  const ChainMode mode = chain_first_mode(n, length);
  const double a = length / static_cast<double>(n - 1);
  std::vector<Vec3> pts(n);
  for (uint32_t v = 1; v < n; ++v) {
    const double x = amp * mode.shape[v];
    const double dx = x - pts[v - 1].x;
    pts[v] = {x, pts[v - 1].y - std::sqrt(a * a - dx * dx), 0.0};
  }
  return pts;
}

// ---- A3: the discrete catenary ---------------------------------------------------------------------------------
// N vertices, both ends pinned at (+-span/2, 0), segments of length a = L/(N-1), unit weight g at each of the N-2
// free vertices. With horizontal tension H, segment j's slope is (V0 - g j)/H, V0 = g (N-2)/2 (symmetry); H is
// found by bisection so that the segments span `span`.
struct Catenary {
  std::vector<Vec3> pts;
  double sag = 0;  // depth of the lowest vertex below the supports
};

inline Catenary discrete_catenary(uint32_t n, double length, double span, double g = kG) {
  const double a = length / static_cast<double>(n - 1);
  const double v0 = g * static_cast<double>(n - 2) / 2.0;
  auto width = [&](double h) {
    double w = 0;
    for (uint32_t j = 0; j + 1 < n; ++j) {
      const double s = (v0 - g * static_cast<double>(j)) / h;
      w += a / std::sqrt(1.0 + s * s);
    }
    return w;
  };
  double lo = 1e-9, hi = 1e9;
  for (int it = 0; it < 300; ++it) {
    const double mid = std::sqrt(lo * hi);
    (width(mid) < span ? lo : hi) = mid;
  }
  const double h = std::sqrt(lo * hi);
  Catenary c;
  c.pts.resize(n);
  c.pts[0] = {-0.5 * span, 0, 0};
  for (uint32_t j = 0; j + 1 < n; ++j) {
    const double s = (v0 - g * static_cast<double>(j)) / h;
    const double cx = a / std::sqrt(1.0 + s * s);
    c.pts[j + 1] = c.pts[j] + Vec3{cx, -s * cx, 0};
  }
  for (const Vec3& p : c.pts) c.sag = std::max(c.sag, -p.y);
  return c;
}

// ---- Running a setup on either side ------------------------------------------------------------------------------
// One strand's simulation: the reference or a GPU instance behind the same two calls.
class StrandRun {
 public:
  virtual ~StrandRun() = default;
  virtual void frame(const TvkSimFrame& f) = 0;
  // Guide vertex positions in simulation space (origin at the instance: the asset origin is added back).
  virtual std::vector<Vec3> positions() = 0;
};
using RunFactory = std::function<std::unique_ptr<StrandRun>(const tressvk::asset::HairAsset&, const TvkSimParams&,
                                                            const TvkSimSettings&)>;

using LengthModel = tressvk::reference::Simulator::LengthModel;

class ReferenceRun final : public StrandRun {
 public:
  ReferenceRun(const tressvk::asset::HairAsset& a, const TvkSimParams& p, const TvkSimSettings& s,
               LengthModel model = LengthModel::kFollowTheLeader)
      : sim_(a, std::span<const TvkSimParams>(&p, 1), s) {
    sim_.set_length_model(model);
  }
  void frame(const TvkSimFrame& f) override { plan_ = sim_.advance(f); }
  std::vector<Vec3> positions() override {
    auto p = sim_.positions();
    const Vec3 o{plan_.sim_origin[0], plan_.sim_origin[1], plan_.sim_origin[2]};
    std::vector<Vec3> out;
    for (size_t i = 0; i < sim_.rest().rest_pos.size(); ++i) out.push_back(p[i] + o);
    return out;
  }
  tressvk::reference::Simulator& sim() { return sim_; }

 private:
  tressvk::reference::Simulator sim_;
  tressvk::reference::FramePlan plan_;
};

inline RunFactory reference_factory(LengthModel model = LengthModel::kFollowTheLeader) {
  return [model](const tressvk::asset::HairAsset& a, const TvkSimParams& p, const TvkSimSettings& s) {
    return std::unique_ptr<StrandRun>(new ReferenceRun(a, p, s, model));
  };
}

// A8. The cantilever: a horizontal strand (L 0.2 m along +x, 2 root vertices pinned, default parameters but
// `iterations` local iterations and damping 0.5 so that it settles) after 10 s under gravity: its tip's sag, m.
inline double cantilever_sag(const RunFactory& make, uint32_t n, double rate, uint32_t iterations) {
  std::vector<Vec3> pts;
  for (uint32_t v = 0; v < n; ++v) pts.push_back({0.2 * v / (n - 1), 0, 0});
  TvkSimParams p = TVK_SIM_PARAMS_DEFAULT_INIT;
  p.local_iterations = iterations;
  p.damping = 0.5f;
  auto run = make(strand_asset(pts, 2), p, settings_at(rate));
  for (uint32_t f = 0; f < 600; ++f) run->frame(still_frame());
  const std::vector<Vec3> x = run->positions();
  return x.front().y - x.back().y;
}

// Upward zero crossings of a sampled signal (linear interpolation), after subtracting its mean.
// ---- The analytic scenarios the reference and the GPU both run (test_analytic.cpp, ../analytic_test.cpp) ---------

// A6. A straight 0.3 m chain of 32 vertices in a steady wind of 4 m/s^2 (no gusts, no cone), damped, 10 s at 240 Hz:
// its tilt from the vertical (degrees), the expected atan(w/g), and the farthest vertex from the straight line (m).
struct WindTilt {
  double angle_deg = 0;
  double expected_deg = 0;
  double off_line = 0;
};
inline WindTilt wind_tilt(const RunFactory& make) {
  std::vector<Vec3> pts;
  for (uint32_t v = 0; v < 32; ++v) pts.push_back({0, -0.3 * v / 31.0, 0});
  TvkSimParams p = chain_params();
  p.damping = 0.3f;
  auto run = make(strand_asset(pts, 1), p, settings_at(240.0));
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
  WindTilt out;
  out.angle_deg = std::atan2(d.x, -d.y) * 180.0 / std::numbers::pi;
  out.expected_deg = std::atan(4.0 / kG) * 180.0 / std::numbers::pi;
  const Vec3 u = normalize(d);
  for (const Vec3& v : x) {
    const Vec3 r = v - x.front();
    out.off_line = std::max(out.off_line, length(r - dot(r, u) * u));
  }
  return out;
}

// A6's bar, the same for the reference and the GPU: the tilt within 0.5 degrees of atan(w/g), and every vertex within
// 1e-3 L of the straight line.
inline void check_wind_tilt(const WindTilt& t) {
  INFO("tilt " << t.angle_deg << " deg, expected " << t.expected_deg << "; off the line " << t.off_line / 0.3 << " L");
  CHECK(std::abs(t.angle_deg - t.expected_deg) <= 0.5);
  CHECK(t.off_line <= 1e-3 * 0.3);
}

// A7. A free 16-vertex strand (nothing pinned, VSP off) falls from rest for `frames` frames at 240 Hz. Verlet
// integrates constant gravity as x_n = x_0 + g h^2 n (n + 1) / 2; the positions after the first frame (the reset
// step, then 4 steps) are compared with the end: the worst error of any vertex's fall relative to the expected fall.
struct FreeFall {
  double fell = 0;      // m, vertex 0
  double expected = 0;  // m
  double worst = 0;     // relative
};
// A7's bar: every vertex's fall within `worst` (relative) of the expected fall.
inline void check_free_fall(const FreeFall& f, double worst) {
  INFO("fell " << f.fell << " m, expected " << f.expected << "; worst relative error " << f.worst);
  CHECK(f.worst <= worst);
}
inline FreeFall free_fall(const RunFactory& make, uint32_t frames) {
  std::vector<Vec3> pts;
  for (uint32_t v = 0; v < 16; ++v) pts.push_back({0.02 * v, 0.001 * v * v, 0});
  auto run = make(strand_asset(pts, 0), chain_params(), settings_at(240.0));
  run->frame(still_frame());
  const std::vector<Vec3> x0 = run->positions();
  uint64_t steps = 4;
  for (uint32_t f = 1; f < frames; ++f) {
    run->frame(still_frame());
    steps += 4;
  }
  const std::vector<Vec3> x = run->positions();
  const double h = 1.0 / 240.0;
  // x0 was taken after 4 steps: the fall between is the difference of the discrete solutions.
  auto fall = [&](uint64_t n) { return 9.81f * h * h * static_cast<double>(n * (n + 1)) / 2.0; };
  FreeFall out;
  out.expected = fall(steps) - fall(4);
  out.fell = x0[0].y - x[0].y;
  for (size_t i = 0; i < x.size(); ++i) {
    out.worst = std::max(out.worst, std::abs((x0[i].y - x[i].y) - out.expected) / out.expected);
    out.worst = std::max(out.worst, std::abs(x0[i].x - x[i].x) / out.expected);
  }
  return out;
}

inline std::vector<double> upward_crossings(const std::vector<double>& t, const std::vector<double>& x) {
  double mean = 0;
  for (double v : x) mean += v;
  mean /= static_cast<double>(x.size());
  std::vector<double> out;
  for (size_t i = 1; i < x.size(); ++i) {
    const double a = x[i - 1] - mean, b = x[i] - mean;
    if (a < 0 && b >= 0) out.push_back(t[i - 1] + (t[i] - t[i - 1]) * (-a / (b - a)));
  }
  return out;
}

struct SwingResult {
  double period = 0;           // mean period from upward zero crossings, s
  double amplitude_ratio = 0;  // geometric mean ratio of successive positive peaks of the tip's x (per period)
  std::vector<double> peaks;
};

// A1/A2: the chain released from its first mode; the tip's x sampled every frame for `seconds`.
inline SwingResult swing(const RunFactory& make, uint32_t n, double rate, float damping, double seconds,
                         double length = 0.3, double amp = 0.003, uint32_t length_iterations = 1) {
  TvkSimParams p = chain_params();
  p.damping = damping;
  p.length_iterations = length_iterations;
  auto run = make(strand_asset(chain_in_mode(n, length, amp), 1), p, settings_at(rate));
  std::vector<double> t, x;
  const uint32_t frames = static_cast<uint32_t>(std::lround(seconds * 60.0));
  for (uint32_t f = 0; f < frames; ++f) {
    run->frame(still_frame());
    t.push_back(static_cast<double>(f) / 60.0);
    x.push_back(run->positions().back().x);
  }
  SwingResult r;
  const std::vector<double> up = upward_crossings(t, x);
  if (up.size() >= 2) r.period = (up.back() - up.front()) / static_cast<double>(up.size() - 1);
  // Positive peaks between consecutive upward crossings (quadratic refinement of the sampled maximum).
  for (size_t k = 0; k + 1 < up.size(); ++k) {
    double best = -1e300;
    size_t bi = 0;
    for (size_t i = 1; i + 1 < t.size(); ++i) {
      if (t[i] < up[k] || t[i] > up[k + 1]) continue;
      if (x[i] > best) {
        best = x[i];
        bi = i;
      }
    }
    if (bi == 0) continue;
    const double y0 = x[bi - 1], y1 = x[bi], y2 = x[bi + 1];
    const double den = y0 - 2 * y1 + y2;
    r.peaks.push_back(den < 0 ? y1 - 0.125 * (y2 - y0) * (y2 - y0) / den : y1);
  }
  if (r.peaks.size() >= 2) {
    r.amplitude_ratio = std::pow(r.peaks.back() / r.peaks.front(), 1.0 / static_cast<double>(r.peaks.size() - 1));
  }
  return r;
}

// ---- The converged reference ----------------------------------------------------------------------------------------
// The guides' positions after each frame of `scene` at step rate `rate`, on the double reference with the planner's
// limits raised (tressvk/reference/converged.hpp, shared with `tressvk-bench sweep`), so the same model can be stepped
// far finer than any GPU setting.
inline std::vector<std::vector<Vec3>> trajectory(const tressvk::asset::HairAsset& a, const TvkSimParams& p,
                                                 double rate, const std::string& scene, uint32_t frames,
                                                 double* median = nullptr,
                                                 LengthModel model = LengthModel::kFollowTheLeader) {
  tressvk::reference::TrajectoryOptions o;
  o.step_rate = rate;
  o.scene = scene;
  o.frames = frames;
  o.configure = [model](tressvk::reference::Simulator& sim) { sim.set_length_model(model); };
  return tressvk::reference::reference_trajectory(a, std::span<const TvkSimParams>(&p, 1), o, median);
}

}  // namespace tvk_analytic
