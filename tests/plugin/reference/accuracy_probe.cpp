// Prints the model-accuracy numbers docs/accuracy.md quotes, from the double reference: the hanging chain's period and
// decay per period (N x step rate x length sweeps), the cantilever's tip sag (N x step rate x local iterations) and
// the convergence of a shaken strand's trajectory as the step rate doubles. A diagnostic, not a test.
//   tressvk_accuracy_probe [chain|cantilever|convergence|rest|looks|perturb|upright|stretch|drift]...
// perturb / upright: the growth of a small perturbation of the initial state (rounding amplification; docs/accuracy.md).
// Environment: TVK_LENGTH_MODEL=newmark | compliant | conservative (the reference's models; default
// follow-the-leader); for `rest`, TVK_LOCAL / TVK_GLOBAL (stiffness) and TVK_LIT (local iterations) override the
// defaults.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numbers>

#include <tressvk/baker/import.hpp>
#include <tressvk/baker/procedural.hpp>
#include <tressvk/reference/near_duplicates.hpp>

#include "analytic.hpp"
#include "helpers.hpp"

using namespace tvk_analytic;

namespace {

// TVK_LENGTH_MODEL (newmark, compliant, conservative) runs every setup on that model (default: follow-the-leader).
LengthModel g_model = LengthModel::kFollowTheLeader;

void chain() {
  std::printf("# hanging chain L 0.3 m, damping 0: period error vs the discrete chain, amplitude kept per period\n");
  std::printf("N,rate_hz,length_iterations,period_s,expected_s,error,kept_per_period\n");
  for (uint32_t n : {16u, 32u, 64u})
    for (double rate : {60.0, 120.0, 240.0, 480.0})
      for (uint32_t li : {1u, 2u, 4u, 8u}) {
        const SwingResult r = swing(reference_factory(g_model), n, rate, 0.0f, 9.0, 0.3, 0.003, li);
        const double e = chain_first_mode(n, 0.3).period;
        std::printf("%u,%.0f,%u,%.4f,%.4f,%+.4f,%.4f\n", n, rate, li, r.period, e, r.period / e - 1.0, r.amplitude_ratio);
      }
}

// A horizontal strand (L 0.2 m, 2 root vertices clamped, defaults; damping from TVK_DAMP where set) under gravity.
auto cantilever_run(uint32_t n, double rate, uint32_t iterations) {
  std::vector<Vec3> pts;
  for (uint32_t v = 0; v < n; ++v) pts.push_back({0.2 * v / (n - 1), 0, 0});
  TvkSimParams p = TVK_SIM_PARAMS_DEFAULT_INIT;
  p.local_iterations = iterations;
  if (const char* e = std::getenv("TVK_DAMP")) p.damping = static_cast<float>(std::atof(e));
  return reference_factory(g_model)(strand_asset(pts, 2), p, settings_at(rate));
}

// Its tip sag after 10 s.
double cantilever_sag(uint32_t n, double rate, uint32_t iterations) {
  auto run = cantilever_run(n, rate, iterations);
  for (uint32_t f = 0; f < 600; ++f) run->frame(still_frame());
  const std::vector<Vec3> x = run->positions();
  return x.front().y - x.back().y;
}

void cantilever_trace(uint32_t n, double rate, uint32_t iterations) {
  auto run = cantilever_run(n, rate, iterations);
  for (uint32_t f = 0; f < 600; ++f) {
    run->frame(still_frame());
    const std::vector<Vec3> x = run->positions();
    double worst = 0;
    for (size_t i = 0; i + 1 < x.size(); ++i) worst = std::max(worst, std::abs(length(x[i + 1] - x[i]) / (0.2 / (n - 1)) - 1));
    if (f % 30 == 0) std::printf("%u %.4f tip %.5f %.5f stretch %.2e\n", f, f / 60.0, x.back().x, x.back().y, worst);
  }
}

void cantilever() {
  std::printf("# cantilever L 0.2 m, defaults: tip sag (mm) after 10 s\n");
  std::printf("N,rate_hz,local_iterations,sag_mm\n");
  for (uint32_t n : {16u, 32u, 64u, 128u}) std::printf("%u,240,2,%.2f\n", n, 1e3 * cantilever_sag(n, 240, 2));
  for (double rate : {60.0, 120.0, 480.0}) std::printf("32,%.0f,2,%.2f\n", rate, 1e3 * cantilever_sag(32, rate, 2));
  for (uint32_t it : {1u, 4u, 8u}) std::printf("32,240,%u,%.2f\n", it, 1e3 * cantilever_sag(32, 240, it));
}

// Richardson-style halving: the trajectory distance between step rates r and 2r (rms and max over 30 frames and
// every guide vertex, / median length), up to 3840 Hz on the CPU, per groom and scene, as a chain (shape terms off)
// and at the defaults.
// TVK_FRAMES (default 30) frames per run, rates from TVK_RATE (default 240) Hz doubling up to 3840, TVK_GROOM (both
// grooms by default); at the defaults TVK_LIT, TVK_LENIT (length iterations), TVK_GLOBAL, TVK_LOCAL, TVK_DAMP and
// TVK_VSP override the parameters.
void convergence() {
  const uint32_t frames = std::getenv("TVK_FRAMES") ? static_cast<uint32_t>(std::atoi(std::getenv("TVK_FRAMES"))) : 30u;
  const double first = std::getenv("TVK_RATE") ? std::atof(std::getenv("TVK_RATE")) : 240.0;
  const char* only = std::getenv("TVK_GROOM");
  std::printf("# trajectory distance between rate r and 2r over %u frames (/ median strand length)\n", frames);
  std::printf("groom,scene,params,rate_hz,rms,max\n");
  for (const char* groom : {"straight", "curly"})
    for (const char* scene : {"settle", "shake"})
      for (int chain_only = 1; chain_only >= 0; --chain_only) {
        if (only && std::strcmp(only, groom) != 0) continue;
        TvkSimParams p = chain_only ? chain_params() : TvkSimParams TVK_SIM_PARAMS_DEFAULT_INIT;
        if (chain_only) p.damping = 0.08f;
        if (!chain_only) {
          if (const char* e = std::getenv("TVK_LIT")) p.local_iterations = static_cast<uint32_t>(std::atoi(e));
          if (const char* e = std::getenv("TVK_LENIT")) p.length_iterations = static_cast<uint32_t>(std::atoi(e));
          if (const char* e = std::getenv("TVK_GLOBAL")) p.global_stiffness = static_cast<float>(std::atof(e));
          if (const char* e = std::getenv("TVK_LOCAL")) p.local_stiffness = static_cast<float>(std::atof(e));
          if (const char* e = std::getenv("TVK_DAMP")) p.damping = static_cast<float>(std::atof(e));
          if (const char* e = std::getenv("TVK_VSP")) p.vsp_coefficient = static_cast<float>(std::atof(e));
        }
        const auto a = tvk_test::groom(groom, 8);
        double median = 0;
        std::vector<std::vector<std::vector<Vec3>>> runs;
        std::vector<double> rates;
        for (double r = first; r <= 3840.0; r *= 2.0) rates.push_back(r);
        for (double r : rates) runs.push_back(trajectory(a, p, r, scene, frames, &median, g_model));
        for (size_t k = 0; k + 1 < runs.size(); ++k) {
          const auto e = tressvk::reference::trajectory_error(runs[k], runs[k + 1], median);
          std::printf("%s,%s,%s,%.0f,%.3e,%.3e\n", groom, scene, chain_only ? "chain" : "defaults", rates[k], e.rms_rel,
                      e.max_rel);
        }
      }
}

// The rest pose without gravity, defaults, per groom: largest distance from the rest pose (/ median length) every
// 10 frames (a stable model stays at rounding level).
void rest() {
  std::printf("groom,frame,max_drift_rel\n");
  for (const char* name : {"straight", "curly", "long128"}) {
    auto a = tvk_test::groom(name, 32, 1);
    TvkSimSettings s = tvk_test::default_settings();
    s.gravity[1] = 0.0f;
    TvkSimParams p = tvk_test::default_params();
    if (const char* e = std::getenv("TVK_LOCAL")) p.local_stiffness = static_cast<float>(std::atof(e));
    if (const char* e = std::getenv("TVK_GLOBAL")) p.global_stiffness = static_cast<float>(std::atof(e));
    if (const char* e = std::getenv("TVK_LIT")) p.local_iterations = static_cast<uint32_t>(std::atoi(e));
    tressvk::reference::Simulator sim = tvk_test::make_sim(a, p, s);
    sim.set_length_model(g_model);
    const auto geo = tressvk::reference::scene_geometry(sim.rest());
    const auto first = sim.advance(tressvk::reference::scene_frame("settle", 0, geo));
    std::vector<Vec3> r;
    for (size_t i = 0; i < sim.rest().rest_pos.size(); ++i) r.push_back(sim.skinned_rest(first.steps[0], i));
    for (uint32_t f = 1; f <= 120; ++f) {
      sim.advance(tressvk::reference::scene_frame("settle", f, geo));
      if (f % 10) continue;
      double worst = 0;
      for (size_t i = 0; i < r.size(); ++i) worst = std::max(worst, length(sim.positions()[i] - r[i]));
      std::printf("%s,%u,%.3e\n", name, f, worst / sim.median_strand_length());
    }
  }
}

// Every built-in groom (64 guides x 32) and, when TVK_RATBOY names Ratboy_mohawk.tfx, the Ratboy mohawk (bones from
// the .tfxbone beside it, baked as tressvk-bake does by default).
std::vector<std::pair<std::string, tressvk::asset::HairAsset>> probe_grooms() {
  std::vector<std::pair<std::string, tressvk::asset::HairAsset>> grooms;
  for (const std::string& name : tressvk::baker::builtin_groom_names()) grooms.emplace_back(name, tvk_test::groom(name, 64));
  if (const char* path = std::getenv("TVK_RATBOY")) {
    tressvk::baker::RawGroom raw = tressvk::baker::import_file(path);
    std::string bones = path;
    bones = bones.substr(0, bones.size() - 4) + ".tfxbone";
    if (std::FILE* f = std::fopen(bones.c_str(), "rb")) {
      std::fclose(f);
      tressvk::baker::apply_tfxbone(raw, bones);
    }
    grooms.emplace_back("ratboy", tressvk::baker::bake(raw, tressvk::baker::BakeOptions{}));
  }
  return grooms;
}

// The look of the grooms at the defaults: every built-in groom (64 guides x 32) and, when TVK_RATBOY names
// Ratboy_mohawk.tfx, the Ratboy mohawk (bones from the .tfxbone beside it, baked as tressvk-bake does by default),
// settled 5 s (settle scene, gravity on) on the follow-the-leader and the compliant model: the distance between the two
// settled shapes (rms and max over the guide vertices, / median strand length) and each one's mean tip drop below its
// rest tip (/ median length).
void looks() {
  std::printf("groom,guides,rms_rel,max_rel,tip_drop_ftl_rel,tip_drop_compliant_rel\n");
  const auto grooms = probe_grooms();
  for (const auto& [name, a] : grooms) {
    std::vector<Vec3> settled[2];
    double drop[2] = {0, 0}, median = 0;
    for (int m = 0; m < 2; ++m) {
      tressvk::reference::Simulator sim = tvk_test::make_sim(a);
      // The second model: the compliant one, or TVK_LENGTH_MODEL's where it names another.
      sim.set_model(m == 0 ? LengthModel::kFollowTheLeader
                           : (g_model == LengthModel::kFollowTheLeader ? LengthModel::kCompliant : g_model));
      const auto geo = tressvk::reference::scene_geometry(sim.rest());
      tressvk::reference::FramePlan plan;
      for (uint32_t f = 0; f < 300; ++f) plan = sim.advance(tressvk::reference::scene_frame("settle", f, geo));
      const uint32_t n = sim.rest().vertices_per_strand;
      const size_t count = sim.rest().rest_pos.size();
      settled[m].assign(sim.positions().begin(), sim.positions().begin() + static_cast<std::ptrdiff_t>(count));
      for (size_t g = 0; g < count / n; ++g) {
        const size_t tip = g * n + n - 1;
        drop[m] += sim.skinned_rest(plan.steps.back(), tip).y - settled[m][tip].y;
      }
      drop[m] /= static_cast<double>(count / n);
      median = sim.median_strand_length();
    }
    double sum = 0, worst = 0;
    for (size_t i = 0; i < settled[0].size(); ++i) {
      const double d = length(settled[0][i] - settled[1][i]);
      sum += d * d;
      worst = std::max(worst, d);
    }
    std::printf("%s,%zu,%.4f,%.4f,%.4f,%.4f\n", name.c_str(), settled[0].size() / a.vertices_per_strand,
                std::sqrt(sum / static_cast<double>(settled[0].size())) / median, worst / median, drop[0] / median,
                drop[1] / median);
  }
}

// Sensitivity to rounding: the same groom and scene twice on the double reference, the second with every free guide
// vertex's position moved by TVK_EPS (default 1e-7) of the median strand length in a pseudo-random direction after
// the first frame; the largest distance between the two (/ median length) every 6 frames. A stable model keeps it
// near TVK_EPS; float rounding on the GPU is such a perturbation every step. TVK_GROOM (straight; neardup: hard case
// 8's groom), TVK_SCENE (shake), TVK_N (32), TVK_GUIDES (16), TVK_FRAMES (60) pick the setup.
void perturb() {
  const char* groom_name = std::getenv("TVK_GROOM") ? std::getenv("TVK_GROOM") : "straight";
  const char* scene = std::getenv("TVK_SCENE") ? std::getenv("TVK_SCENE") : "shake";
  const uint32_t n = std::getenv("TVK_N") ? static_cast<uint32_t>(std::atoi(std::getenv("TVK_N"))) : 32u;
  const uint32_t guides = std::getenv("TVK_GUIDES") ? static_cast<uint32_t>(std::atoi(std::getenv("TVK_GUIDES"))) : 16u;
  const uint32_t frames = std::getenv("TVK_FRAMES") ? static_cast<uint32_t>(std::atoi(std::getenv("TVK_FRAMES"))) : 60u;
  const double eps = std::getenv("TVK_EPS") ? std::atof(std::getenv("TVK_EPS")) : 1e-7;
  // TVK_GROOM=neardup: hard case 8's groom (straight strands with sub-micrometre segments).
  const bool neardup = std::strcmp(groom_name, "neardup") == 0;
  const auto a = neardup ? tressvk::reference::with_near_duplicate_vertices(tvk_test::groom("straight", guides, 0, n))
                         : tvk_test::groom(groom_name, guides, 0, n);
  TvkSimParams p = tvk_test::default_params();
  if (const char* e = std::getenv("TVK_LOCAL")) p.local_stiffness = static_cast<float>(std::atof(e));
  if (const char* e = std::getenv("TVK_GLOBAL")) p.global_stiffness = static_cast<float>(std::atof(e));
  if (const char* e = std::getenv("TVK_LIT")) p.local_iterations = static_cast<uint32_t>(std::atoi(e));
  if (const char* e = std::getenv("TVK_DAMP")) p.damping = static_cast<float>(std::atof(e));
  TvkSimSettings s = tvk_test::default_settings();
  if (const char* e = std::getenv("TVK_RATE")) s.time.step_rate = static_cast<float>(std::atof(e));
  tressvk::reference::Simulator sa = tvk_test::make_sim(a, p, s), sb = tvk_test::make_sim(a, p, s);
  sa.set_model(g_model);
  sb.set_model(g_model);
  const auto geo = tressvk::reference::scene_geometry(sa.rest());
  sa.advance(tressvk::reference::scene_frame(scene, 0, geo));
  sb.advance(tressvk::reference::scene_frame(scene, 0, geo));
  const double median = sa.median_strand_length();
  uint64_t seed = 12345;
  auto rnd = [&] {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(seed >> 11) / 9007199254740992.0 * 2.0 - 1.0;
  };
  auto pos = sb.mutable_positions();
  for (size_t i = 0; i < sb.rest().rest_pos.size(); ++i) {
    if (!(sb.rest().inv_mass[i] > 0.0)) continue;
    pos[i] += eps * median * Vec3{rnd(), rnd(), rnd()};
  }
  std::printf("frame,max_rel\n");
  for (uint32_t f = 1; f <= frames; ++f) {
    sa.advance(tressvk::reference::scene_frame(scene, f, geo));
    sb.advance(tressvk::reference::scene_frame(scene, f, geo));
    if (f % 6 && f != 1) continue;
    const size_t count = sa.rest().rest_pos.size();
    std::printf("%u,%.3e\n", f, tvk_test::max_rel(sa.positions().first(count), sb.positions().first(count), median));
  }
  if (std::getenv("TVK_PER_STRAND")) {
    const uint32_t nv = sa.rest().vertices_per_strand;
    for (uint32_t g = 0; g < sa.rest().guide_count; ++g) {
      const size_t b = size_t{g} * nv;
      double worst = 0;
      for (uint32_t v = 0; v < nv; ++v) worst = std::max(worst, length(sa.positions()[b + v] - sb.positions()[b + v]));
      const Vec3 d = sa.rest().rest_pos[b + nv - 1] - sa.rest().rest_pos[b];
      const Vec3 tip = sa.positions()[b + nv - 1] - sa.positions()[b];
      std::printf("strand %u rest dir y %.3f  now tip dir y %.3f  apart %.3e\n", g, d.y / length(d), tip.y / length(tip),
                  worst / median);
    }
  }
}

// One straight strand (L 0.15 m, N from TVK_N, 2 root vertices pinned, defaults) standing TVK_ANGLE degrees above
// the horizontal (default 76: the straight groom's most upright strand) under gravity, head still, twice: the second
// with its free vertices moved by TVK_EPS (1e-12) of its length after the first frame. Every 15 frames: the tip's
// height, the fastest vertex (m/s) and the distance between the two runs (/ L).
void upright() {
  const uint32_t n = std::getenv("TVK_N") ? static_cast<uint32_t>(std::atoi(std::getenv("TVK_N"))) : 32u;
  const double angle = (std::getenv("TVK_ANGLE") ? std::atof(std::getenv("TVK_ANGLE")) : 76.0) * 3.14159265358979 / 180;
  const double eps = std::getenv("TVK_EPS") ? std::atof(std::getenv("TVK_EPS")) : 1e-12;
  const uint32_t frames = std::getenv("TVK_FRAMES") ? static_cast<uint32_t>(std::atoi(std::getenv("TVK_FRAMES"))) : 300u;
  const double len = 0.15;
  std::vector<Vec3> pts;
  for (uint32_t v = 0; v < n; ++v) pts.push_back({len * v / (n - 1) * std::cos(angle), len * v / (n - 1) * std::sin(angle), 0});
  TvkSimParams p = TVK_SIM_PARAMS_DEFAULT_INIT;
  if (const char* e = std::getenv("TVK_LOCAL")) p.local_stiffness = static_cast<float>(std::atof(e));
  if (const char* e = std::getenv("TVK_GLOBAL")) p.global_stiffness = static_cast<float>(std::atof(e));
  if (const char* e = std::getenv("TVK_LIT")) p.local_iterations = static_cast<uint32_t>(std::atoi(e));
  if (const char* e = std::getenv("TVK_DAMP")) p.damping = static_cast<float>(std::atof(e));
  const double rate = std::getenv("TVK_RATE") ? std::atof(std::getenv("TVK_RATE")) : 240.0;
  const auto a = strand_asset(pts, 2);
  ReferenceRun ra(a, p, settings_at(rate), g_model), rb(a, p, settings_at(rate), g_model);
  ra.frame(still_frame());
  rb.frame(still_frame());
  auto pos = rb.sim().mutable_positions();
  uint64_t seed = 12345;
  auto rnd = [&] {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(seed >> 11) / 9007199254740992.0 * 2.0 - 1.0;
  };
  for (uint32_t v = 2; v < n; ++v) pos[v] += eps * len * Vec3{rnd(), rnd(), rnd()};
  std::printf("frame,tip_y,max_speed,apart_rel\n");
  for (uint32_t f = 1; f <= frames; ++f) {
    ra.frame(still_frame());
    rb.frame(still_frame());
    if (f % 15) continue;
    const auto xa = ra.sim().positions(), xb = rb.sim().positions(), qa = ra.sim().prev_positions();
    double apart = 0, speed = 0;
    for (uint32_t v = 0; v < n; ++v) {
      apart = std::max(apart, length(xa[v] - xb[v]));
      speed = std::max(speed, length(xa[v] - qa[v]) * rate);
    }
    std::printf("%u,%.5f,%.3e,%.3e\n", f, xa[n - 1].y, speed, apart / len);
  }
  if (std::getenv("TVK_PROFILE")) {
    const auto x = ra.sim().positions(), q = ra.sim().prev_positions(), r = ra.sim().prevprev_positions();
    for (uint32_t v = 0; v < n; ++v) {
      const Vec3 s1 = x[v] - q[v], s0 = q[v] - r[v];
      const double la = length(s1), lb = length(s0);
      std::printf("v %2u  x %.4f y %.4f  speed %.3e  cos(step, previous step) %+.3f\n", v, x[v].x, x[v].y, la * rate,
                  la > 0 && lb > 0 ? dot(s1, s0) / (la * lb) : 0.0);
    }
  }
}

// The compliant length solve's worst stretch per 6 frames (reference::stretch) on TVK_GROOM x TVK_GUIDES x TVK_N in
// TVK_SCENE at TVK_RATE Hz with TVK_LIT local iterations (defaults: long128 8 x 128, run, 240 Hz, 2: hard case 2); TVK_NEAR_DUP=1 instead puts sub-micrometre segments into
// the straight groom as hard case 8 does (reference::with_near_duplicate_vertices); TVK_RATBOY=…/Ratboy_mohawk.tfx the
// Ratboy mohawk with its bones, baked at TVK_N vertices. TVK_EVERY prints every frame; TVK_DEBUG lists the segments
// more than 5 % off their length in a frame whose worst is.
void stretch_probe() {
  const char* groom_name = std::getenv("TVK_GROOM") ? std::getenv("TVK_GROOM") : "long128";
  const char* scene = std::getenv("TVK_SCENE") ? std::getenv("TVK_SCENE") : "run";
  const uint32_t n = std::getenv("TVK_N") ? static_cast<uint32_t>(std::atoi(std::getenv("TVK_N"))) : 128u;
  const uint32_t guides = std::getenv("TVK_GUIDES") ? static_cast<uint32_t>(std::atoi(std::getenv("TVK_GUIDES"))) : 8u;
  auto a = tvk_test::groom(groom_name, guides, 0, n);
  if (std::getenv("TVK_NEAR_DUP"))
    a = tressvk::reference::with_near_duplicate_vertices(tvk_test::groom("straight", 8));
  if (const char* path = std::getenv("TVK_RATBOY")) {  // the Ratboy mohawk baked at TVK_N vertices instead
    tressvk::baker::RawGroom raw = tressvk::baker::import_file(path);
    std::string bones = path;
    tressvk::baker::apply_tfxbone(raw, bones.substr(0, bones.size() - 4) + ".tfxbone");
    tressvk::baker::BakeOptions options;
    options.vertices_per_strand = n;
    a = tressvk::baker::bake(raw, options);
  }
  TvkSimSettings s = tvk_test::default_settings();
  if (const char* e = std::getenv("TVK_RATE")) s.time.step_rate = static_cast<float>(std::atof(e));
  TvkSimParams p = tvk_test::default_params();
  if (const char* e = std::getenv("TVK_LIT")) p.local_iterations = static_cast<uint32_t>(std::atoi(e));
  tressvk::reference::Simulator sim = tvk_test::make_sim(a, p, s);
  sim.set_model(g_model);
  const auto geo = tressvk::reference::scene_geometry(sim.rest());
  std::printf("frame,max_stretch\n");
  double worst = 0;
  for (uint32_t f = 0; f < 60; ++f) {
    sim.advance(tressvk::reference::scene_frame(scene, f, geo));
    const double st = tressvk::reference::stretch(sim.positions().first(sim.rest().rest_pos.size()), sim.rest()).max;
    worst = std::max(worst, st);
    if (f % 6 == 5 || std::getenv("TVK_EVERY")) std::printf("%u,%.3e\n", f, st);
    if (std::getenv("TVK_DEBUG") && st > 0.05) {
      const uint32_t nv = sim.rest().vertices_per_strand;
      for (size_t i = 0; i + 1 < sim.rest().rest_pos.size(); ++i) {
        if ((i + 1) % nv == 0) continue;
        const double r = sim.rest().rest_length[i];
        const double l = length(sim.positions()[i + 1] - sim.positions()[i]);
        if (r > 0 && std::abs(l / r - 1) > 0.05)
          std::printf("  strand %zu seg %zu rest %.3e now %.3e inv_mass %g %g strand_len %.3e\n", i / nv, i % nv, r, l,
                      sim.rest().inv_mass[i], sim.rest().inv_mass[i + 1], sim.rest().strand_length[i / nv]);
      }
    }
  }
  std::printf("worst,%.3e\n", worst);
}

// Uniform motion: each built-in groom (64 guides x 32; the Ratboy mohawk where TVK_RATBOY names it) settled 5 s under a
// still head, then carried forward (+z) at a speed that ramps smoothly to TVK_SPEED m/s (default 1.5, a walk) over
// 1 s and holds it for 5 s, head still otherwise. Prints how far the hair then sits from its settled shape, seen from
// the head (each vertex less its strand's skinned root; rms and max over the guide vertices, / median strand length)
// and the mean tip's move backwards (-z, / median length): the model's damping acts on world velocity, so uniform
// motion is not rest in it (an air drag of about damping x 60 per second times the speed).
void drift() {
  const double speed = std::getenv("TVK_SPEED") ? std::atof(std::getenv("TVK_SPEED")) : 1.5;
  std::printf("groom,speed_m_s,rms_rel,max_rel,tip_back_rel\n");
  const auto grooms = probe_grooms();
  for (const auto& [name, a] : grooms) {
    tressvk::reference::Simulator sim = tvk_test::make_sim(a);
    sim.set_model(g_model);
    const auto geo = tressvk::reference::scene_geometry(sim.rest());
    const size_t count = sim.rest().rest_pos.size();
    const uint32_t n = sim.rest().vertices_per_strand;
    // Positions seen from the head: less the skinned rest root of their strand (simulation space follows the head).
    const auto from_head = [&](const tressvk::reference::FramePlan& plan) {
      std::vector<Vec3> out(count);
      for (size_t i = 0; i < count; ++i) out[i] = sim.positions()[i] - sim.skinned_rest(plan.steps.back(), i - i % n);
      return out;
    };
    tressvk::reference::FramePlan plan;
    for (uint32_t f = 0; f < 300; ++f) plan = sim.advance(tressvk::reference::scene_frame("settle", f, geo));
    const std::vector<Vec3> settled = from_head(plan);
    double z = 0;
    const double dt = tressvk::reference::kSceneFrameDt;
    for (uint32_t f = 0; f < 360; ++f) {
      const double t = (f + 1) * dt;
      const double v = t < 1.0 ? speed * 0.5 * (1.0 - std::cos(std::numbers::pi * t)) : speed;
      z += v * dt;
      TvkSimFrame fr = tressvk::reference::scene_frame("settle", 300 + f, geo);
      fr.transform.translation[2] += z;
      plan = sim.advance(fr);
    }
    const std::vector<Vec3> moving = from_head(plan);
    double sum = 0, worst = 0, back = 0;
    for (size_t i = 0; i < count; ++i) {
      const Vec3 p = moving[i];
      const double d = length(p - settled[i]);
      sum += d * d;
      worst = std::max(worst, d);
      if (i % n == n - 1) back += settled[i].z - p.z;
    }
    const double median = sim.median_strand_length();
    std::printf("%s,%.3f,%.4f,%.4f,%.4f\n", name.c_str(), speed, std::sqrt(sum / static_cast<double>(count)) / median,
                worst / median, back / static_cast<double>(count / n) / median);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (const char* m = std::getenv("TVK_LENGTH_MODEL"); m && std::strcmp(m, "newmark") == 0) g_model = LengthModel::kNewmark;
  if (const char* m = std::getenv("TVK_LENGTH_MODEL"); m && std::strcmp(m, "compliant") == 0) g_model = LengthModel::kCompliant;
  if (const char* m = std::getenv("TVK_LENGTH_MODEL"); m && std::strcmp(m, "conservative") == 0) g_model = LengthModel::kConservative;
  for (int i = 1; i < argc || argc == 1; ++i) {
    const char* what = argc == 1 ? "all" : argv[i];
    const bool all = std::strcmp(what, "all") == 0;
    if (all || std::strcmp(what, "chain") == 0) chain();
    if (all || std::strcmp(what, "cantilever") == 0) cantilever();
    if (all || std::strcmp(what, "convergence") == 0) convergence();
    if (std::strcmp(what, "rest") == 0) rest();
    if (std::strcmp(what, "looks") == 0) looks();
    if (std::strcmp(what, "drift") == 0) drift();
    if (std::strcmp(what, "perturb") == 0) perturb();
    if (std::strcmp(what, "upright") == 0) upright();
    if (std::strcmp(what, "stretch") == 0) stretch_probe();
    if (std::strcmp(what, "trace") == 0) {
      cantilever_trace(static_cast<uint32_t>(std::atoi(argv[i + 1])), std::atof(argv[i + 2]),
                       static_cast<uint32_t>(std::atoi(argv[i + 3])));
      return 0;
    }
    if (argc == 1) break;
  }
  return 0;
}
