// Follow hairs only for the strands the host draws (tressvk_set_draw_strands): a groom drawn thinned by LOD does not
// pay for the follows it does not show. The simulation writes the follows of the drawn prefix (guides, then follow
// layers) and nothing else; raising the count writes the rest in the next frame, waking sleeping guides to do it.
// Run by the default entry and by every frame kernel's ctest entry (8-vertex strands: the lane kernels' subgroup
// variant on lavapipe).
#include "sim_harness.hpp"

#include <tressvk/baker/procedural.hpp>
#include <tressvk/reference/scenes.hpp>

#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <cmath>
#include <string>

using namespace tressvk;

namespace {

constexpr float kQuietFrames = float(TVK_ASLEEP_QUIET_FRAMES);

asset::HairAsset follow_groom() {
  baker::BuiltinGroomOptions options;
  options.guide_count = 16;
  options.follow_per_guide = 2;
  options.vertices_per_strand = 8;
  return baker::make_builtin_groom("straight", options);
}

// Rendered strands [first, last) of a and b hold the same bits (positions and tangents).
bool same_strands(const test::GpuState& a, const test::GpuState& b, uint32_t n, uint32_t first, uint32_t last) {
  const size_t lo = size_t{first} * n, hi = size_t{last} * n;
  return std::equal(a.pos.begin() + lo, a.pos.begin() + hi, b.pos.begin() + lo) &&
         std::equal(a.tangent.begin() + lo, a.tangent.begin() + hi, b.tangent.begin() + lo);
}

// Rendered strands [first, last) of a and b as stored: positions relative to their guide's anchor (the harness adds
// the anchor, which moves with the head whether or not a strand is written). Tangents are the guides' alone (a
// follow's is its guide's), so they say nothing about the follows.
bool same_stored(const test::GpuState& a, const test::GpuState& b, uint32_t n, uint32_t guides, uint32_t first,
                 uint32_t last) {
  for (size_t i = size_t{first} * n; i < size_t{last} * n; ++i) {
    const size_t g = i / n % guides;
    for (int c = 0; c < 3; ++c)
      if (a.pos[i][c] - a.anchors[g][c] != b.pos[i][c] - b.anchors[g][c]) return false;
  }
  return true;
}

// The largest distance between the positions of rendered strands [first, last) of a and b.
double farthest(const test::GpuState& a, const test::GpuState& b, uint32_t n, uint32_t first, uint32_t last) {
  double d = 0;
  for (size_t i = size_t{first} * n; i < size_t{last} * n; ++i)
    for (int c = 0; c < 3; ++c) {
      const double e = std::abs(a.pos[i][c] - b.pos[i][c]);
      d = std::isfinite(e) ? std::max(d, e) : HUGE_VAL;  // an unwritten buffer may hold anything
    }
  return d;
}

}  // namespace

TEST_CASE("follow hairs are written only for the strands the host draws", "[plugin][simulation]") {
  const asset::HairAsset hair = follow_groom();
  const uint32_t n = hair.vertices_per_strand;
  const uint32_t guides = hair.guide_count();
  const uint32_t rendered = guides * 3;
  const uint32_t drawn = guides + guides / 2;  // the guides and half of the first follow layer
  const std::vector<TvkSimParams> params(std::max<size_t>(1, hair.groups.size()), TvkSimParams TVK_SIM_PARAMS_DEFAULT_INIT);
  test::PluginContext ctx = test::create_plugin_context();
  test::AssetHandle a(test::load_asset(ctx.get(), hair));

  SECTION("the drawn strands are those of an instance that draws every strand, bit for bit; the others are not written") {
    const TvkSimSettings settings = TVK_SIM_SETTINGS_DEFAULT_INIT;
    test::GpuInstance all(ctx.get(), a.get(), params, settings), some(ctx.get(), a.get(), params, settings);
    CHECK(tressvk_set_draw_strands(some.handle(), rendered + 1) == TVK_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(tressvk_last_error(ctx.get())).find("tressvk_set_draw_strands") != std::string::npos);
    REQUIRE(tressvk_set_draw_strands(some.handle(), drawn) == TVK_SUCCESS);
    const reference::SceneGeometry geometry =
        reference::scene_geometry(reference::Simulator(hair, params, settings).rest());
    test::GpuState first;
    double moved = 0;  // how far the undrawn follows of the instance that draws them moved: the test means something
    for (uint32_t f = 0; f < 20; ++f) {
      const TvkSimFrame frame = reference::scene_frame("shake", f, geometry);
      test::run_frame_batched(ctx.get(), {&all, &some}, {frame, frame});
      INFO("frame " << f);
      CHECK(same_strands(all.state(), some.state(), n, 0, drawn));
      if (f == 0) first = some.state();
      CHECK(same_stored(first, some.state(), n, guides, drawn, rendered));  // never written: what the buffer held
      for (size_t i = size_t{drawn} * n; i < size_t{rendered} * n; ++i)
        for (int c = 0; c < 3; ++c) moved = std::max(moved, std::abs(all.state().pos[i][c] - first.pos[i][c]));
    }
    INFO("the undrawn follows moved up to " << moved << " m on the instance that draws them");
    CHECK(moved > 1e-3);
    // Every strand again: the next frame writes them all.
    REQUIRE(tressvk_set_draw_strands(some.handle(), 0) == TVK_SUCCESS);
    const TvkSimFrame frame = reference::scene_frame("shake", 20, geometry);
    test::run_frame_batched(ctx.get(), {&all, &some}, {frame, frame});
    CHECK(same_strands(all.state(), some.state(), n, 0, rendered));
  }

  SECTION("drawing more strands wakes a sleeping groom to write their follows") {
    TvkSimSettings settings = TVK_SIM_SETTINGS_DEFAULT_INIT;
    settings.gravity[1] = 0.0f;  // the rest pose is at rest: every guide sleeps within a few still frames
    test::GpuInstance all(ctx.get(), a.get(), params, settings), some(ctx.get(), a.get(), params, settings);
    REQUIRE(tressvk_set_draw_strands(some.handle(), guides) == TVK_SUCCESS);  // the guides alone
    const reference::SceneGeometry geometry =
        reference::scene_geometry(reference::Simulator(hair, params, settings).rest());
    const auto asleep = [](const test::GpuState& s) {
      return static_cast<size_t>(
          std::count_if(s.anchors.begin(), s.anchors.end(), [](const auto& an) { return an[3] >= kQuietFrames; }));
    };
    uint32_t f = 0;
    for (; f < 120 && (f == 0 || asleep(some.state()) < guides); ++f) {
      const TvkSimFrame frame = reference::scene_frame("settle", f, geometry);
      test::run_frame_batched(ctx.get(), {&all, &some}, {frame, frame});
    }
    INFO("frames until every guide slept: " << f);
    REQUIRE(asleep(some.state()) == guides);
    CHECK(same_strands(all.state(), some.state(), n, 0, guides));
    const double garbage = farthest(all.state(), some.state(), n, guides, rendered);
    REQUIRE(tressvk_set_draw_strands(some.handle(), 0) == TVK_SUCCESS);
    const TvkSimFrame frame = reference::scene_frame("settle", f, geometry);  // still in every other input
    test::run_frame_batched(ctx.get(), {&all, &some}, {frame, frame});
    // The woken groom ran a step at rest (its guides move by less than the sleeping threshold, 1e-6 of the strand a
    // step, while the other one sleeps on), so its follows are where the sleeping twin's are to well under 1e-5 m
    // (strands of about 0.3 m); unwritten, they would be what the buffer held (`garbage`, metres off or more).
    const double off = farthest(all.state(), some.state(), n, guides, rendered);
    INFO("the follows before the wake were " << garbage << " m off the twin's, after it " << off << " m");
    CHECK(garbage > 1e-3);  // not written before: the test means something
    CHECK(asleep(some.state()) == 0);
    CHECK(off < 1e-5);
  }
}
