// Sleeping strands (shaders/sim/layout.glsl, "Sleeping strands"; TvkSimSettings::sleep_below): a groom at rest under a
// still head stops being simulated, keeps its state, and wakes when any input changes. Run by every frame kernel's
// ctest entry (the run kernel by default, runs of 8, the one-thread kernel, both lane-kernel models).
#include "sim_harness.hpp"

#include <tressvk/baker/procedural.hpp>
#include <tressvk/reference/metrics.hpp>
#include <tressvk/reference/scenes.hpp>

#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <cmath>

using namespace tressvk;

namespace {

constexpr float kQuietFrames = float(TVK_ASLEEP_QUIET_FRAMES);  // tressvk.h: TvkInstanceBuffers::anchors

size_t asleep(const test::GpuState& s) {
  return static_cast<size_t>(
      std::count_if(s.anchors.begin(), s.anchors.end(), [](const auto& a) { return a[3] >= kQuietFrames; }));
}

asset::HairAsset sleep_groom(uint32_t vertices_per_strand) {
  baker::BuiltinGroomOptions options;
  options.guide_count = 16;
  options.follow_per_guide = 1;
  options.vertices_per_strand = vertices_per_strand;
  return baker::make_builtin_groom("straight", options);
}

// A groom loaded once with two instances: one that may sleep (the default settings) and a twin that never does
// (sleep_below 0). Until the first sleeps they compute the same bits (the count does not touch the physics); after,
// the second is what sleeping left out.
struct Twins {
  explicit Twins(uint32_t vertices_per_strand)
      : hair(sleep_groom(vertices_per_strand)),
        params(std::max<size_t>(1, hair.groups.size()), TvkSimParams TVK_SIM_PARAMS_DEFAULT_INIT),
        ctx(test::create_plugin_context()),
        a(test::load_asset(ctx.get(), hair)),
        gpu(ctx.get(), a.get(), params, settings),
        awake(ctx.get(), a.get(), params, never_sleeps()) {}
  static TvkSimSettings never_sleeps() {
    TvkSimSettings s = TVK_SIM_SETTINGS_DEFAULT_INIT;
    s.sleep_below = 0.0f;
    return s;
  }
  asset::HairAsset hair;
  std::vector<TvkSimParams> params;
  TvkSimSettings settings = TVK_SIM_SETTINGS_DEFAULT_INIT;
  test::PluginContext ctx;
  test::AssetHandle a;
  test::GpuInstance gpu, awake;
};

// Settles the groom under a still head (the `settle` scene) until every guide sleeps, then checks what sleeping
// means: a sleeping strand is not simulated (a vertex moved by hand stays where it was put), the state it keeps is
// where the reference would have let it settle, and the first frame that is not still wakes every guide.
void check_sleep(uint32_t vertices_per_strand) {
  Twins twins(vertices_per_strand);
  const asset::HairAsset& hair = twins.hair;
  test::GpuInstance& gpu = twins.gpu;
  test::GpuInstance& awake = twins.awake;
  const test::PluginContext& ctx = twins.ctx;
  const reference::Simulator ref(hair, twins.params, twins.settings);
  const reference::SceneGeometry geometry = reference::scene_geometry(ref.rest());
  const double median = ref.median_strand_length();
  const uint32_t n = hair.vertices_per_strand;
  const size_t guide_vertices = size_t{hair.guide_count()} * n;
  const auto guides = [&](const std::vector<test::Point>& p) {
    return std::span<const test::Point>(p.data(), guide_vertices);
  };
  uint32_t f = 0;
  const auto both = [&](const TvkSimFrame& frame) {
    test::run_frame_batched(ctx.get(), {&gpu, &awake}, {frame, frame});
    ++f;
  };
  // The straight groom falls from horizontal and swings to rest: at the default damping its motion decays by about
  // e^-4.8 a second, so a swing of the strand's length comes down to 1e-6 of it per step in a few seconds.
  constexpr uint32_t kMaxFrames = 900;
  while (f < kMaxFrames && (f == 0 || asleep(gpu.state()) < hair.guide_count()))
    both(reference::scene_frame("settle", f, geometry));
  INFO("frames until every guide slept: " << f);
  REQUIRE(asleep(gpu.state()) == hair.guide_count());
  CHECK(asleep(awake.state()) == 0);

  // What sleeping leaves out: 2 s more of the same still frames.
  const test::GpuState slept = gpu.state();
  for (uint32_t k = 0; k < 120; ++k) both(reference::scene_frame("settle", f, geometry));
  const auto frozen = reference::position_error(guides(slept.pos), guides(gpu.state().pos), median);
  const auto missed = reference::position_error(guides(gpu.state().pos), guides(awake.state().pos), median);
  INFO("motion of the sleeping groom in 2 s: " << frozen.max_rel << "; of the one awake: " << missed.max_rel);
  CHECK(frozen.max_rel == 0.0);  // nothing was simulated: not one bit moved
  // No vertex moved more than 1e-6 of the median strand per step in 3 measured frames. What was left to move decays
  // with the damping (0.98 of the velocity kept per step at the default: up to 50x a step's move) and the shape
  // constraints' slowest modes settle slower still (measured: follow-the-leader 3.4e-5 at 32 vertices and 2.5e-6 at
  // 8, the compliant model 5.6e-5, and 1.1e-4 with a threshold relative to each strand's own length). The bar, 2e-4 of
  // the strand (60 um on a 30 cm strand), is far under what a person sees and under the model's own error
  // at the default settings (docs/accuracy.md: 1e-2 and more against the converged reference). A threshold of 1e-7
  // would leave 10x less but sits on float32's rounding of a settled strand (3e-8 never slept at 32 vertices, nor
  // did the compliant model's 8-vertex strands all at 1e-7 in 15 s). Measured: see INFO.
  CHECK(missed.max_rel <= 2e-4);

  // Not simulated: guide 2's tip, moved by hand half its segment's length further out, stays there through still
  // frames, its segment stretched by half.
  const size_t tip = size_t{2} * n + n - 1;
  const test::Point before = gpu.state().pos[tip];
  const test::Point parent = gpu.state().pos[tip - 1];
  test::Point poked{};
  for (int c = 0; c < 3; ++c) poked[c] = before[c] + 0.5 * (before[c] - parent[c]);
  const std::array<float, 4>& anchor = gpu.state().anchors[2];
  gpu.poke_position(tip, {static_cast<float>(poked[0] - anchor[0]), static_cast<float>(poked[1] - anchor[1]),
                          static_cast<float>(poked[2] - anchor[2]), 1.0f});
  both(reference::scene_frame("settle", f, geometry));
  CHECK(asleep(gpu.state()) == hair.guide_count());
  const auto stretched = reference::stretch(guides(gpu.state().pos), ref.rest());
  INFO("worst stretch while asleep: " << stretched.max);
  CHECK(std::abs(stretched.max - 0.5) < 1e-3);

  // Any change of input wakes every guide: here the head moves by 0.1 mm, and the length pass pulls the segment back
  // (to within the 5 % that the default settings keep in every scene; follow-the-leader restores it exactly, the
  // compliant model to 1e-3 in that frame).
  TvkSimFrame nudged = reference::scene_frame("settle", f, geometry);
  nudged.transform.translation[0] += 1e-4;
  both(nudged);
  CHECK(asleep(gpu.state()) == 0);
  for (const auto& an : gpu.state().anchors) CHECK(an[3] == 0.0f);
  const auto st = reference::stretch(guides(gpu.state().pos), ref.rest());
  INFO("worst stretch after waking: " << st.max);
  CHECK(st.max <= 0.05);
}

}  // namespace

TEST_CASE("a still groom at rest sleeps and wakes when an input changes", "[plugin][simulation]") {
  check_sleep(32);
}

// On the lane kernels' ctest entries: lavapipe's 8-lane subgroups run their subgroup variant.
TEST_CASE("a still groom of 8-vertex strands at rest sleeps and wakes when an input changes", "[plugin][simulation]") {
  check_sleep(8);
}

TEST_CASE("with sleep_below 0 no guide ever sleeps", "[plugin][simulation]") {
  const asset::HairAsset hair = sleep_groom(8);
  const std::vector<TvkSimParams> params(1, TvkSimParams TVK_SIM_PARAMS_DEFAULT_INIT);
  TvkSimSettings settings = TVK_SIM_SETTINGS_DEFAULT_INIT;
  settings.sleep_below = 0.0f;
  test::PluginContext ctx = test::create_plugin_context();
  test::AssetHandle a(test::load_asset(ctx.get(), hair));
  test::GpuInstance gpu(ctx.get(), a.get(), params, settings);
  const reference::SceneGeometry geometry = reference::scene_geometry(reference::Simulator(hair, params, settings).rest());
  for (uint32_t f = 0; f < 600; ++f) gpu.run_frame(reference::scene_frame("settle", f, geometry));
  CHECK(asleep(gpu.state()) == 0);
  for (const auto& an : gpu.state().anchors) CHECK(an[3] == 0.0f);
}

// What is still: a steady wind is an input like any other (the groom settles in it and sleeps), a gusting one changes
// every step (its strength follows the time), so no frame is still and no guide sleeps.
TEST_CASE("a groom sleeps in a steady wind and never in a gusting one", "[plugin][simulation]") {
  const asset::HairAsset hair = sleep_groom(8);
  const std::vector<TvkSimParams> params(1, TvkSimParams TVK_SIM_PARAMS_DEFAULT_INIT);
  const TvkSimSettings settings = TVK_SIM_SETTINGS_DEFAULT_INIT;
  test::PluginContext ctx = test::create_plugin_context();
  test::AssetHandle a(test::load_asset(ctx.get(), hair));
  test::GpuInstance steady(ctx.get(), a.get(), params, settings);
  test::GpuInstance gusting(ctx.get(), a.get(), params, settings);
  const reference::SceneGeometry geometry = reference::scene_geometry(reference::Simulator(hair, params, settings).rest());
  uint32_t f = 0;
  for (; f < 900 && (f == 0 || asleep(steady.state()) < hair.guide_count()); ++f) {
    TvkSimFrame calm = reference::scene_frame("settle", f, geometry);
    calm.wind.strength = 3.0f;
    calm.wind.gust_amplitude = 0.0f;
    TvkSimFrame gusty = calm;
    gusty.wind.gust_amplitude = 0.5f;
    test::run_frame_batched(ctx.get(), {&steady, &gusting}, {calm, gusty});
  }
  INFO("frames until every guide slept in the steady wind: " << f);
  CHECK(asleep(steady.state()) == hair.guide_count());
  CHECK(asleep(gusting.state()) == 0);
  for (const auto& an : gusting.state().anchors) CHECK(an[3] == 0.0f);
}

// An instance whose every guide sleeps costs nothing: once a still frame ended with every guide asleep (its frame
// slot's awake word, read frames_in_flight frames later), the plugin records no dispatch for it until a frame is not
// still, and the state it keeps is the one it slept in. Beside it in the same batch, a twin that never sleeps keeps
// its dispatch every frame.
TEST_CASE("an instance whose every guide sleeps records no dispatch until a frame is not still", "[plugin][simulation]") {
  Twins twins(8);
  const asset::HairAsset& hair = twins.hair;
  test::GpuInstance& gpu = twins.gpu;
  test::GpuInstance& awake = twins.awake;
  const reference::SceneGeometry geometry =
      reference::scene_geometry(reference::Simulator(hair, twins.params, twins.settings).rest());
  const auto recorded = [&] { return tressvk_get_recorded_passes(twins.ctx.get(), nullptr, 0); };
  const auto moved = [](const test::GpuState& x, const test::GpuState& y) {
    return reference::position_error(std::span<const test::Point>(x.pos), std::span<const test::Point>(y.pos), 1.0).max_rel;
  };
  uint32_t f = 0;
  while (f < 900 && (f == 0 || asleep(gpu.state()) < hair.guide_count()))
    gpu.run_frame(reference::scene_frame("settle", f++, geometry));
  INFO("frames until every guide slept: " << f);
  REQUIRE(asleep(gpu.state()) == hair.guide_count());
  // The next frame runs no guide; it and the one after are recorded (2 frames in flight: their slots' words, read as
  // each slot comes round again, still answer for frames in which guides ran); after them nothing is recorded.
  const test::GpuState slept = gpu.state();
  for (uint32_t k = 0; k < 2; ++k) gpu.run_frame(reference::scene_frame("settle", f++, geometry));
  for (uint32_t k = 0; k < 30; ++k) {
    gpu.run_frame(reference::scene_frame("settle", f++, geometry));
    CHECK(recorded() == 0);
    CHECK(tressvk_get_recorded_dispatches(twins.ctx.get()) == 0);
  }
  CHECK(moved(slept, gpu.state()) == 0.0);
  // In a batch with an instance that runs, only that one is dispatched (one frame kernel), and each keeps its own.
  const TvkSimFrame still = reference::scene_frame("settle", f++, geometry);
  test::run_frame_batched(twins.ctx.get(), {&gpu, &awake}, {still, still});
  CHECK(recorded() == 1);
  CHECK(tressvk_get_recorded_dispatches(twins.ctx.get()) == 1);  // the awake twin's frame kernel alone
  CHECK(moved(slept, gpu.state()) == 0.0);
  CHECK(asleep(awake.state()) == 0);
  // The first frame that is not still runs and wakes every guide; the still frames after it run again until the
  // guides have slept once more.
  TvkSimFrame nudged = reference::scene_frame("settle", f++, geometry);
  nudged.transform.translation[0] += 1e-4;
  gpu.run_frame(nudged);
  CHECK(recorded() == 1);
  CHECK(asleep(gpu.state()) == 0);
  gpu.run_frame(nudged);
  CHECK(recorded() == 1);
}

// Strands that never come to rest (follow-the-leader's local shape keeps a limit cycle on curls at 2 iterations,
// docs/accuracy.md "At rest") still sleep once the still run has lasted long enough for their group's damping to take
// any motion the inputs gave them below the threshold (simulate.cpp, a settled still run: an amplitude keeps
// velocity_keep^(steps / 2) = exp(-30 damping t), so at the default damping 0.08 that is ln(1e6) / (30 * 0.08) =
// 5.76 s), and what they still move then is the model's own. Without damping nothing is forced.
TEST_CASE("a still groom whose strands never rest sleeps once its damping has settled it", "[plugin][simulation]") {
  baker::BuiltinGroomOptions options;
  options.guide_count = 8;
  options.follow_per_guide = 1;
  options.vertices_per_strand = 32;
  const asset::HairAsset hair = baker::make_builtin_groom("curly", options);
  const std::vector<TvkSimParams> params(std::max<size_t>(1, hair.groups.size()), TvkSimParams TVK_SIM_PARAMS_DEFAULT_INIT);
  std::vector<TvkSimParams> undamped = params;
  for (TvkSimParams& p : undamped) p.damping = 0.0f;
  const TvkSimSettings settings = TVK_SIM_SETTINGS_DEFAULT_INIT;
  TvkSimSettings never = settings;
  never.sleep_below = 0.0f;
  test::PluginContext ctx = test::create_plugin_context();
  test::AssetHandle a(test::load_asset(ctx.get(), hair));
  test::GpuInstance gpu(ctx.get(), a.get(), params, settings);
  test::GpuInstance awake(ctx.get(), a.get(), params, never);   // the same physics, never asleep
  test::GpuInstance free(ctx.get(), a.get(), undamped, settings);  // no damping: never settled
  const reference::Simulator ref(hair, params, settings);
  const reference::SceneGeometry geometry = reference::scene_geometry(ref.rest());
  const double median = ref.median_strand_length();
  const size_t guide_vertices = size_t{hair.guide_count()} * hair.vertices_per_strand;
  const auto guides = [&](const std::vector<test::Point>& p) {
    return std::span<const test::Point>(p.data(), guide_vertices);
  };
  // 5.76 s of still frames at 60 fps from the scene's first still frame, then three measured frames (one in four).
  constexpr uint32_t kBefore = 330, kAfter = 380;
  uint32_t f = 0;
  const auto run_to = [&](uint32_t end) {
    for (; f < end; ++f) {
      const TvkSimFrame frame = reference::scene_frame("settle", f, geometry);
      test::run_frame_batched(ctx.get(), {&gpu, &awake, &free}, {frame, frame, frame});
    }
  };
  run_to(kBefore);
  const size_t asleep_before = asleep(gpu.state());
  // Until then only the motion rule sleeps a guide, so the instance still follows its never-sleeping twin (reported).
  const auto before_settled = reference::position_error(guides(gpu.state().pos), guides(awake.state().pos), median);
  run_to(kAfter);
  const size_t asleep_after = asleep(gpu.state());
  // What sleeping leaves out from then: the limit cycle, against the twin that keeps running it.
  const test::GpuState slept = gpu.state();
  run_to(kAfter + 120);
  const auto frozen = reference::position_error(guides(slept.pos), guides(gpu.state().pos), median);
  const auto missed = reference::position_error(guides(gpu.state().pos), guides(awake.state().pos), median);
  TvkSimSettings resolved{};
  REQUIRE(tressvk_get_sim_settings(gpu.handle(), &resolved) == TVK_SUCCESS);
  INFO("model " << resolved.model << ": guides asleep at frame " << kBefore << ": " << asleep_before << ", at "
                << kAfter << ": " << asleep_after << " of " << hair.guide_count() << "; the twin's distance before: "
                << before_settled.max_rel << "; what 2 s asleep left out: " << missed.max_rel
                << "; undamped asleep: " << asleep(free.state()));
  CHECK(asleep(awake.state()) == 0);
  switch (resolved.model) {
    case TVK_SIM_MODEL_FOLLOW_THE_LEADER:
      // Its curls keep cycling until the damping has settled them: not every guide sleeps before then, all after.
      CHECK(asleep_before < hair.guide_count());
      CHECK(asleep_after == hair.guide_count());
      CHECK(frozen.max_rel == 0.0);
      // The guides that slept by the motion rule hold a state within 2e-4 of the twin's (the first test's bar, with
      // its reasons); the cycling ones are where their cycle was, within its amplitude (measured 0.028 of the median
      // strand). The bar is a tenth of the strand, what a person would see as a strand out of place: the cycle is
      // the model's own motion, not one the inputs gave it.
      CHECK(missed.max_rel <= 0.1);
      // Without damping nothing forces them asleep (some rest by the motion rule: measured 2 of 8).
      CHECK(asleep(free.state()) < hair.guide_count());
      break;
    case TVK_SIM_MODEL_CONSERVATIVE:
      // Its curls come to rest, damped or not (measured: every guide asleep by frame 330 both ways).
      CHECK(asleep_after == hair.guide_count());
      CHECK(frozen.max_rel == 0.0);
      CHECK(missed.max_rel <= 2e-4);
      break;
    default:
      // The compliant model's held targets keep its curls flying (docs/accuracy.md), faster than the settled rule's
      // 1e-2 of the strand a step: they stay awake.
      CHECK(asleep_after == 0);
      break;
  }
}
