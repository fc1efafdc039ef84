// A groom under gravity with a still head comes to rest (docs/accuracy.md, "At rest"): after 25 s of `settle` at the
// default settings no vertex moves more than 1e-9 of the median strand length per step. The GPU's sleeping
// (TvkSimSettings::sleep_below, 1e-6 per step by default) rests on it: a groom the model keeps moving never sleeps,
// and a flicker at rest is what issue 10 asks the model not to have. tressvk_rest_probe prints the same per guide.
#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>

#include "helpers.hpp"

#include <tressvk/baker/bake.hpp>
#include <tressvk/baker/import.hpp>

using namespace tvk_test;

namespace {

// The largest move of a guide vertex per step over one frame after `frames` frames of settle, / median length.
double motion_at_rest(const tressvk::asset::HairAsset& a, uint32_t local_iterations, std::optional<Simulator::SimModel> model,
                      uint32_t frames = 1500, TvkSimParams p = default_params()) {
  p.local_iterations = local_iterations;
  Simulator sim = make_sim(a, p);
  if (model) sim.set_model(*model);
  const SceneGeometry geo = scene_geometry(sim.rest());
  for (uint32_t f = 0; f < frames; ++f) sim.advance(scene_frame("settle", f, geo));
  const std::vector<Vec3> before(sim.positions().begin(), sim.positions().end());
  const FramePlan plan = sim.advance(scene_frame("settle", frames, geo));
  const size_t guide_vertices = size_t{sim.rest().guide_count} * sim.rest().vertices_per_strand;
  double m = 0;
  for (size_t i = 0; i < guide_vertices; ++i) m = std::max(m, length(sim.positions()[i] - before[i]));
  return m / static_cast<double>(plan.steps.size()) / sim.rest().median_length;
}

constexpr double kAtRest = 1e-9;  // measured 1e-16..1e-15 where the model rests; the limit cycles below are 1e-3..1e-1

}  // namespace

TEST_CASE("rest: straight and 128-vertex grooms come to rest under gravity in every model", "[reference][rest]") {
  for (const char* name : {"straight", "long128"}) {
    const auto a = groom(name, 8);
    for (Simulator::SimModel m : {Simulator::SimModel::kFollowTheLeader, Simulator::SimModel::kCompliant, Simulator::SimModel::kConservative}) {
      const double motion = motion_at_rest(a, 2, m);
      INFO(name << ", model " << static_cast<int>(m) << ": " << motion << " of the median length per step");
      CHECK(motion <= kAtRest);
    }
  }
}

TEST_CASE("rest: the curly groom comes to rest with 3 or more local iterations (follow-the-leader)", "[reference][rest]") {
  const auto a = groom("curly", 8);
  for (uint32_t it : {3u, 4u}) {
    const double motion = motion_at_rest(a, it, Simulator::SimModel::kFollowTheLeader);
    INFO(it << " local iterations: " << motion << " of the median length per step");
    CHECK(motion <= kAtRest);
  }
}

TEST_CASE("rest: the curly groom comes to rest under the conservative local shape", "[reference][rest]") {
  const double motion = motion_at_rest(groom("curly", 8), 2, Simulator::SimModel::kConservative);
  INFO(motion << " of the median length per step");
  CHECK(motion <= kAtRest);
}

// Known to fail (docs/accuracy.md, "At rest"): at the default 2 local iterations (and at 1) follow-the-leader's
// curls keep a limit cycle at rest (64 guides: 36 of them, up to 4.3e-3 of the strand per step, 0.045 net over a
// second), whatever the length pass's velocity correction (0 .. 1); 3 iterations and more come to rest.
TEST_CASE("rest: the curly groom comes to rest at the default 2 local iterations (follow-the-leader)",
          "[reference][rest][!shouldfail]") {
  const double motion = motion_at_rest(groom("curly", 8), 2, Simulator::SimModel::kFollowTheLeader);
  INFO(motion << " of the median length per step");
  CHECK(motion <= kAtRest);
}

// Known to fail: the compliant model's curls start moving by themselves under gravity and settle into 0.09 of the
// strand per step (about 10 m/s) within 5 s, at 2, 4 and 8 local iterations; the conservative local shape, which
// solves the same constraints with their full gradient, rests (above).
TEST_CASE("rest: the curly groom comes to rest (compliant model)", "[reference][rest][!shouldfail]") {
  const double motion = motion_at_rest(groom("curly", 8), 2, Simulator::SimModel::kCompliant);
  INFO(motion << " of the median length per step");
  CHECK(motion <= kAtRest);
}

namespace {

// The settled pose (guide vertices after `frames` frames of settle) at a step rate and local iteration count.
std::vector<Vec3> settled_pose(const tressvk::asset::HairAsset& a, Simulator::SimModel model, float step_rate,
                               uint32_t local_iterations, double& median, uint32_t frames = 1500) {
  TvkSimParams p = default_params();
  p.local_iterations = local_iterations;
  TvkSimSettings s = default_settings();
  s.time.step_rate = step_rate;
  Simulator sim = make_sim(a, p, s);
  sim.set_model(model);
  const SceneGeometry geo = scene_geometry(sim.rest());
  for (uint32_t f = 0; f < frames; ++f) sim.advance(scene_frame("settle", f, geo));
  const size_t guide_vertices = size_t{sim.rest().guide_count} * sim.rest().vertices_per_strand;
  median = sim.rest().median_length;
  return {sim.positions().begin(), sim.positions().begin() + static_cast<std::ptrdiff_t>(guide_vertices)};
}

// The rms distance between two poses over the median strand length.
double rms_rel(const std::vector<Vec3>& x, const std::vector<Vec3>& y, double median) {
  double sum = 0;
  for (size_t i = 0; i < x.size(); ++i) sum += dot(x[i] - y[i], x[i] - y[i]);
  return std::sqrt(sum / static_cast<double>(x.size())) / median;
}

// A groomer's look should not depend on the step rate or the iteration count a platform runs (issue 10): the settled
// curly groom at 120 and 480 Hz and at 1 and 4 local iterations against 240 Hz and 2 iterations, rms over the guide
// vertices. The bar, 1e-3 of the median strand length, is a tenth of a millimetre on a 10 cm strand; the conservative
// model measures at most 2.5e-5 here (8 guides; 64: 3.1e-5, both at 120 Hz with 1 iteration), follow-the-leader
// 0.045-0.18 (64 guides, 60 Hz included: 0.043-0.405).
constexpr double kSameLook = 1e-3;

void check_look_independent_of_settings(Simulator::SimModel model) {
  const auto a = groom("curly", 8);
  double median = 0;
  const std::vector<Vec3> base = settled_pose(a, model, 240.0f, 2, median);
  struct Setting { float rate; uint32_t it; };
  for (const Setting st : {Setting{120.0f, 1}, Setting{120.0f, 2}, Setting{240.0f, 1}, Setting{240.0f, 4},
                           Setting{480.0f, 2}}) {
    const double rms = rms_rel(settled_pose(a, model, st.rate, st.it, median), base, median);
    INFO(st.rate << " Hz, " << st.it << " local iterations: the settled pose is " << rms
                 << " of the median length (rms) from 240 Hz with 2");
    CHECK(rms <= kSameLook);
  }
}

}  // namespace

TEST_CASE("rest: the conservative model's settled curls look the same at every step rate and iteration count",
          "[reference][rest]") {
  check_look_independent_of_settings(Simulator::SimModel::kConservative);
}

// Known to fail (docs/accuracy.md, "The settled look against the settings"): follow-the-leader's stiffness is a
// fraction per step and per iteration, so its settled curls change with both (64 guides: 60 Hz 0.405 rms, the tips
// 0.70 of the length lower; 120 Hz 0.111; 480 Hz 0.057; 1 / 3 / 4 iterations 0.067 / 0.043 / 0.046), and the Ratboy
// mohawk's more (120 Hz: 0.42 rms, the tips 0.37 of the length lower; 480 Hz: 0.30, 0.44 higher).
TEST_CASE("rest: the settled curls look the same at every step rate and iteration count (follow-the-leader)",
          "[reference][rest][!shouldfail]") {
  check_look_independent_of_settings(Simulator::SimModel::kFollowTheLeader);
}

namespace {

// Ratboy's guides that follow-the-leader keeps moving at rest (the mohawk baked with its bones and 2 follow hairs, as
// `tressvk_rest_probe` and the GPU tables use it): upright strands fallen over with a kink (docs/accuracy.md "At
// rest"), alone (strands do not interact), with the whole groom's rule for short strands.
std::optional<double> ratboy_flickering_guides_at_rest(Simulator::SimModel model) {
  const char* dir = std::getenv("TRESSVK_DATA_DIR");
  const std::filesystem::path tfx = std::filesystem::path(dir ? dir : "") / "tressfx" / "ratboy" / "Ratboy_mohawk.tfx";
  if (!dir || !std::filesystem::exists(tfx)) return std::nullopt;
  tressvk::baker::RawGroom raw = tressvk::baker::import_tfx(tfx);
  tressvk::baker::apply_tfxbone(raw, std::filesystem::path(tfx).replace_extension(".tfxbone"));
  tressvk::baker::BakeOptions options;
  options.follow_per_guide = 2;
  double whole_median = 0;
  const tressvk::asset::HairAsset a =
      only_guides(tressvk::baker::bake(raw, options), "268,824,1283,1422,1595,2211", whole_median);
  TvkSimParams p = default_params();
  p.rigid_below = static_cast<float>(0.45 * whole_median);
  return motion_at_rest(a, 2, model, 1500, p);
}

}  // namespace

// The conservative model rests where follow-the-leader keeps a limit cycle on a real groom (2.7e-3 of these guides'
// median length per step on follow-the-leader; 2.4e-15 conservative).
TEST_CASE("rest: Ratboy's six flickering strands come to rest on the conservative model", "[reference][rest][data]") {
  const std::optional<double> motion = ratboy_flickering_guides_at_rest(Simulator::SimModel::kConservative);
  if (!motion) SKIP("no shared data (TRESSVK_DATA_DIR): Ratboy_mohawk.tfx");
  INFO(*motion << " of the median length per step");
  CHECK(*motion <= kAtRest);
}

// Known to fail: follow-the-leader's Gauss-Seidel sweep keeps them moving at every split of its moves that leaves the
// hair its look (docs/accuracy.md, "At rest").
TEST_CASE("rest: Ratboy's six flickering strands come to rest (follow-the-leader)", "[reference][rest][data][!shouldfail]") {
  const std::optional<double> motion = ratboy_flickering_guides_at_rest(Simulator::SimModel::kFollowTheLeader);
  if (!motion) SKIP("no shared data (TRESSVK_DATA_DIR): Ratboy_mohawk.tfx");
  INFO(*motion << " of the median length per step");
  CHECK(*motion <= kAtRest);
}
