// Golden-image and property tests of the hair renderer, on the demo's scene and frame (the same code the main
// job runs), on the shared validated device.
//
// The default path is the compute strand rasterizer (default_scene_256.png); the raster path keeps its own golden
// image (default_scene_256_raster.png).
//
// Scene: the sphere head sample (long128) with a reduced groom (400 guides x 4), camera framing the head, 256x256,
// no head motion and a zero time step, so the hair is in its baked rest pose: the images test the renderer and
// do not change when the simulation model is tuned.
//
// Golden tolerance (documented in docs/rendering.md): mean channel difference <= 1.5 / 255 and at most 0.5 % of
// the pixels with a channel off by more than 32 / 255. Why: a 1-ulp difference in a projected position moves a
// pixel's analytic coverage by far less than 1/255 almost everywhere, but where it flips a depth test (two strands
// crossing at equal depth, the opaque-core threshold) one pixel changes by up to a strand's full contrast. Such
// pixels are isolated; a real regression (colour, width, lighting, shadows) moves the mean or thousands of pixels.
// Regenerate with TRESSVK_UPDATE_GOLDEN=1 after an intended change, and look at the new image.
#include <tressvk/test/vulkan.hpp>

#include "demo_app.hpp"
#include "still_frame.hpp"

#include <tressvk/engine/png.hpp>

#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

using tressvk::demo::DemoApp;
using tressvk::demo::Options;
using tressvk::demo::PassFlavour;
using tressvk::engine::Pixels;

constexpr uint32_t kSize = 256;

Options golden_options() {
  Options o = tressvk::test::still_frame_options(kSize, 400, 3);
  // The renderer's images keep the sphere head with the long128 groom: they test the renderer, and the bundled
  // head sample has its own poster tests (poster_test.cpp).
  o.sample = tressvk::demo::Sample::sphere;
  return o;
}

struct Render {
  Pixels pixels;
  uint32_t strands_drawn = 0;
  uint32_t total_strands = 0;
};

Render render(const Options& options, PassFlavour flavour = PassFlavour::dynamic_rendering, uint32_t frames = 2) {
  DemoApp app(tressvk::test::device(), options, flavour);
  Render out;
  out.total_strands = app.asset_info().total_strands;
  app.run(frames, [&](tressvk::demo::FrameReport& f) {
    out.pixels = std::move(f.pixels);
    out.strands_drawn = f.strands_drawn;
  });
  return out;
}

std::filesystem::path out_dir() { return TRESSVK_RENDER_TEST_OUT; }

double luminance(const Pixels& p, uint32_t x, uint32_t y) {
  const auto c = p.rgba8(x, y);
  return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

// `owner`: the one test whose image becomes the golden image under TRESSVK_UPDATE_GOLDEN=1; the others only compare.
void check_golden(const Pixels& actual, const std::string& name, bool owner = false) {
  const std::filesystem::path golden = std::filesystem::path(TRESSVK_GOLDEN_DIR) / (name + ".png");
  tressvk::engine::write_png(out_dir() / (name + ".actual.png"), actual);
  const char* update = std::getenv("TRESSVK_UPDATE_GOLDEN");
  if (owner && update && std::string(update) == "1") {
    tressvk::engine::write_png(golden, actual);
    WARN("updated " << golden.string());
    return;
  }
  REQUIRE(std::filesystem::exists(golden));
  const Pixels expected = tressvk::engine::read_png(golden);
  const auto diff = tressvk::engine::compare_rgba8(actual, expected, 32);
  tressvk::engine::write_png(out_dir() / (name + ".diff.png"), tressvk::engine::diff_image(actual, expected));
  INFO("golden " << golden.string() << ": mean channel diff " << diff.mean_channel_diff << ", max "
                 << diff.max_channel_diff << ", pixels over 32: " << diff.fraction_over * 100.0
                 << " % (actual and diff images in " << out_dir().string() << ")");
  CHECK(diff.mean_channel_diff <= 1.5);
  CHECK(diff.fraction_over <= 0.005);
}

}  // namespace

TEST_CASE("render: golden image of the default scene (dynamic rendering)", "[render][vulkan]") {
  const Render r = render(golden_options());
  check_golden(r.pixels, "default_scene_256", /*owner=*/true);
  // The hair is actually there: hair-coloured (red > blue) pixels cover a good part of the frame centre.
  uint32_t hair_like = 0;
  for (uint32_t y = kSize / 4; y < 3 * kSize / 4; ++y)
    for (uint32_t x = kSize / 4; x < 3 * kSize / 4; ++x) {
      const auto c = r.pixels.rgba8(x, y);
      if (c[0] > c[2] + 12) ++hair_like;
    }
  CHECK(hair_like > kSize * kSize / 16);
}

TEST_CASE("render: the raster path (--path raster) still draws its golden image", "[render][vulkan]") {
  // The quads drawn in the host's pass (tressvk_cmd_draw_hair), kept beside the compute path; its golden image is
  // the one this path drew before the compute path became the default.
  Options o = golden_options();
  o.hair_path = tressvk::demo::HairPath::raster;
  check_golden(render(o).pixels, "default_scene_256_raster", /*owner=*/true);
}

TEST_CASE("render: the raster path in a VkRenderPass draws the same image as with dynamic rendering",
          "[render][vulkan]") {
  Options o = golden_options();
  o.hair_path = tressvk::demo::HairPath::raster;
  const Render dynamic = render(o, PassFlavour::dynamic_rendering);
  const Render pass = render(o, PassFlavour::render_pass);
  const auto diff = tressvk::engine::compare_rgba8(dynamic.pixels, pass.pixels, 2);
  INFO("max channel diff " << diff.max_channel_diff << ", pixels over 2: " << diff.pixels_over);
  CHECK(diff.fraction_over <= 0.001);
}

TEST_CASE("render: the VkRenderPass flavour draws the same image as dynamic rendering", "[render][vulkan]") {
  const Render dynamic = render(golden_options(), PassFlavour::dynamic_rendering);
  const Render pass = render(golden_options(), PassFlavour::render_pass);
  const auto diff = tressvk::engine::compare_rgba8(dynamic.pixels, pass.pixels, 2);
  INFO("max channel diff " << diff.max_channel_diff << ", pixels over 2: " << diff.pixels_over);
  // Same pipelines but for the render pass object, same draws: identical up to rasterizer rounding.
  CHECK(diff.fraction_over <= 0.001);
  check_golden(pass.pixels, "default_scene_256");
}

TEST_CASE("render: shadows darken the floor under the head and the hair, and nothing else", "[render][vulkan]") {
  Options on = golden_options();
  Options off = golden_options();
  off.shadows = false;
  const Render lit = render(off);
  const Render shadowed = render(on);
  tressvk::engine::write_png(out_dir() / "shadows_off.png", lit.pixels);
  tressvk::engine::write_png(out_dir() / "shadows_on.png", shadowed.pixels);
  uint64_t darker = 0, brighter = 0;
  double floor_lit = 0, floor_shadowed = 0;
  uint32_t floor_pixels = 0;
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x < kSize; ++x) {
      const double a = luminance(lit.pixels, x, y), b = luminance(shadowed.pixels, x, y);
      if (b < a - 8) ++darker;
      // Shadows only take light away; the geometry of the main pass is the same either way.
      if (b > a + 2) ++brighter;
      if (y >= 17 * kSize / 25 && y < 21 * kSize / 25) {  // the floor band under the head (fixed framing)
        floor_lit += a;
        floor_shadowed += b;
        ++floor_pixels;
      }
    }
  INFO("pixels darker with shadows: " << darker << ", brighter: " << brighter);
  CHECK(darker > kSize * kSize / 50);
  CHECK(brighter <= kSize * kSize / 1000);
  CHECK(floor_shadowed < floor_lit);
}

TEST_CASE("render: LOD at distance draws fewer strands and stays close to the full render", "[render][vulkan]") {
  Options full = golden_options();
  full.camera_distance = 6.0f;
  Options lod = full;
  lod.lod_start = 1.0f;
  lod.lod_end = 5.0f;
  lod.lod_min_fraction = 0.25f;
  const Render a = render(full);
  const Render b = render(lod);
  tressvk::engine::write_png(out_dir() / "lod_full.png", a.pixels);
  tressvk::engine::write_png(out_dir() / "lod_thinned.png", b.pixels);
  CHECK(a.strands_drawn == a.total_strands);
  CHECK(b.strands_drawn <= a.total_strands / 4 + 1);
  // Tolerance: at 6 m the head is ~15 px wide; fewer, wider strands keep the coverage, so the hair keeps its
  // overall colour and extent. Individual pixels inside the hair may differ (different strands), so the check is on
  // the mean difference and on the hair's summed darkness against the background.
  const auto diff = tressvk::engine::compare_rgba8(a.pixels, b.pixels, 48);
  INFO("mean channel diff " << diff.mean_channel_diff << ", pixels over 48: " << diff.pixels_over);
  // Measured here: mean 0.20, 38 pixels over 48. The limit on single pixels is 0.2 % of the frame (131 pixels):
  // a thinned strand set differs pixel by pixel where a kept strand is drawn wider in place of dropped ones.
  CHECK(diff.mean_channel_diff <= 1.0);
  CHECK(diff.fraction_over <= 0.002);
}

TEST_CASE("render: sub-pixel hair keeps its coverage as it moves (no shimmer, no vanishing)", "[render][vulkan]") {
  // At 6 m the strands are ~0.1 px wide. Move the camera by fractions of a pixel: the hair's summed coverage
  // (its total contrast against the unchanged floor and background) must stay the same, which it would not if
  // thin strands popped in and out between pixel centres.
  Options base = golden_options();
  base.camera_distance = 6.0f;
  base.shadows = false;  // shadows would move with the shadow-map texel grid, which is not under test here
  const auto contrast = [](const Pixels& p, const Pixels& background) {
    double sum = 0;
    for (uint32_t y = 0; y < p.height; ++y)
      for (uint32_t x = 0; x < p.width; ++x) sum += std::abs(luminance(p, x, y) - luminance(background, x, y));
    return sum;
  };
  // The reference background at the same camera: the head with the fewest strands the groom allows, so that only
  // the hair's contrast is summed.
  const auto hair_contrast = [&](const Options& o) {
    Options empty = o;
    empty.guides = 16;
    empty.follows = 0;
    return contrast(render(o).pixels, render(empty).pixels);
  };
  const double c0 = hair_contrast(base);
  CHECK(c0 > 0.0);
  for (const float step : {0.0007f, 0.0013f, 0.0021f}) {  // 0.25 .. 0.8 px of apparent motion
    Options moved = base;
    moved.camera_distance = 6.0f + step * 6.0f;
    const double c = hair_contrast(moved);
    INFO("hair contrast at +" << step * 6.0f << " m: " << c << " vs " << c0);
    // Tolerance (measured: 0.3-0.5 %): the hair's projected size changes by < 0.05 % with the distance; 1.5 %
    // covers that and the rounding of the 8-bit output over the few hundred hair pixels.
    CHECK(std::abs(c - c0) <= 0.015 * c0);
  }
}

TEST_CASE("render: the scene 10 km from the world origin renders like the golden image", "[render][vulkan]") {
  // The camera, the lights and the instance all move by 10 km; the plugin subtracts the simulation origin and
  // the engine the eye position in double, so the GPU sees the same small numbers and the golden tolerance holds.
  Options far = golden_options();
  far.world_offset = {10000.0, 25.0, -10000.0};
  check_golden(render(far).pixels, "default_scene_256");
}
