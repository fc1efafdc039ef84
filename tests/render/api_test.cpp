// The rendering C interface refuses bad input with TVK_ERROR_INVALID_ARGUMENT and a message naming what was
// wrong (no exception crosses it), and creates and destroys a renderer cleanly under validation.
#include <tressvk/test/vulkan.hpp>

#include <tressvk/asset_io.hpp>
#include <tressvk/baker/procedural.hpp>
#include <tressvk/engine/image.hpp>
#include <tressvk/host/glue.hpp>

#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <iterator>
#include <string>
#include <vector>

namespace {

// A built-in groom loaded through the plugin (the host glue records its upload and waits for it).
TvkAsset load_builtin(TvkContext ctx, const char* name, const tressvk::baker::BuiltinGroomOptions& options) {
  return tressvk::host::load_asset(tressvk::test::device(), ctx,
                                   tressvk::asset::write(tressvk::baker::make_builtin_groom(name, options)));
}

// A renderer of the shading passes into RGBA8 with a 32-bit depth.
TvkRenderer create_rgba8_renderer(TvkContext ctx) {
  TvkRendererCreateInfo ri{};
  ri.struct_size = sizeof(ri);
  ri.shading.color_format = VK_FORMAT_R8G8B8A8_UNORM;
  ri.shading.depth_format = VK_FORMAT_D32_SFLOAT;
  TvkRenderer renderer = nullptr;
  REQUIRE(tressvk_create_renderer(ctx, &ri, &renderer) == TVK_SUCCESS);
  return renderer;
}

}  // namespace

TEST_CASE("render API: invalid arguments are refused with a message", "[render][vulkan]") {
  auto ctx = tressvk::test::create_plugin_context();
  TvkRenderer renderer = nullptr;
  CHECK(tressvk_create_renderer(ctx.get(), nullptr, &renderer) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(renderer == nullptr);
  CHECK(std::string(tressvk_last_error(ctx.get())).find("struct_size") != std::string::npos);

  TvkRendererCreateInfo info{};
  info.struct_size = sizeof(info);
  CHECK(tressvk_create_renderer(ctx.get(), &info, &renderer) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(std::string(tressvk_last_error(ctx.get())).find("color_format") != std::string::npos);

  info.shading.color_format = VK_FORMAT_R8G8B8A8_SRGB;
  info.shading.depth_format = VK_FORMAT_D32_SFLOAT;
  REQUIRE(tressvk_create_renderer(ctx.get(), &info, &renderer) == TVK_SUCCESS);
  REQUIRE(renderer != nullptr);

  tressvk::test::run_commands([&](VkCommandBuffer cmd) {
    CHECK(tressvk_cmd_draw_hair(renderer, cmd, nullptr) == TVK_ERROR_INVALID_ARGUMENT);
    TvkDrawInfo draw{};
    draw.struct_size = sizeof(draw) - 1;
    CHECK(tressvk_cmd_draw_hair(renderer, cmd, &draw) == TVK_ERROR_INVALID_ARGUMENT);
    draw.struct_size = sizeof(draw);
    CHECK(tressvk_cmd_draw_hair(renderer, cmd, &draw) == TVK_ERROR_INVALID_ARGUMENT);  // no instance, no view
    CHECK(std::string(tressvk_last_error(ctx.get())).find("tressvk_cmd_draw_hair") != std::string::npos);
    // This renderer has no shadow target: the shadow call says so.
    CHECK(tressvk_cmd_draw_shadow(renderer, cmd, &draw) == TVK_ERROR_INVALID_ARGUMENT);
    CHECK(tressvk_cmd_draw_hair(nullptr, cmd, &draw) == TVK_ERROR_INVALID_ARGUMENT);
  });
  CHECK(tressvk_get_last_drawn_strands(renderer) == 0);
  tressvk_destroy_renderer(renderer);
  tressvk_destroy_renderer(nullptr);  // allowed, does nothing
}

TEST_CASE("render API: two instances with their own materials in one pass", "[render][vulkan]") {
  // Two heads of the procedural groom side by side, red and blue, drawn in one dynamic-rendering pass: each call
  // takes its own constant block from the frame's ring slice, and each instance keeps its own material.
  auto& dev = tressvk::test::device();
  auto ctx = tressvk::test::create_plugin_context();
  tressvk::baker::BuiltinGroomOptions groom_options;
  groom_options.guide_count = 200;
  TvkAsset asset = load_builtin(ctx.get(), "straight", groom_options);
  TvkInstance heads[2] = {};
  for (TvkInstance& h : heads) {
    TvkInstanceCreateInfo ic{};
    ic.struct_size = sizeof(ic);
    ic.asset = asset;
    REQUIRE(tressvk_create_instance(ctx.get(), &ic, &h) == TVK_SUCCESS);
  }
  TvkRenderer renderer = create_rgba8_renderer(ctx.get());

  constexpr uint32_t kW = 128, kH = 64;
  const auto target = tressvk::engine::create_offscreen_target(dev, kW, kH, VK_FORMAT_R8G8B8A8_UNORM);
  // Camera on +z looking at the origin; heads at x = -0.2 and +0.2 (orthographic, 0.8 m x 0.4 m).
  const double sx = 2.0 / 0.8, sy = -2.0 / 0.4, sz = 1.0 / 2.0;  // Vulkan: y down, depth 0..1 over 2 m
  TvkView view{};
  const double vp[16] = {sx, 0, 0, 0, 0, sy, 0, 0, 0, 0, -sz, 0, 0, 0, 1.0 * sz, 1};  // z = 1 m -> depth 0
  std::copy(std::begin(vp), std::end(vp), view.view_projection);
  view.eye[2] = 1.0;
  view.orthographic = 1;
  view.direction[2] = -1.0f;
  view.width = kW;
  view.height = kH;
  TvkHairMaterial materials[2] = {TVK_HAIR_MATERIAL_DEFAULT_INIT, TVK_HAIR_MATERIAL_DEFAULT_INIT};
  materials[0].base_color[0] = materials[0].tip_color[0] = 0.8f;  // red
  materials[1].base_color[2] = materials[1].tip_color[2] = 0.8f;  // blue
  for (TvkHairMaterial& m : materials) {
    m.strand_width = 0.003f;
    m.color_variation = 0.0f;
  }
  TvkLight light{};
  light.type = TVK_LIGHT_DIRECTIONAL;
  light.direction[2] = -1.0f;
  light.color[0] = light.color[1] = light.color[2] = 1.0f;
  light.intensity = 1.0f;

  tressvk::test::run_commands([&](VkCommandBuffer cmd) {
    REQUIRE(tressvk_new_frame(ctx.get()) == TVK_SUCCESS);
    for (int i = 0; i < 2; ++i) {
      TvkSimFrame frame{};
      frame.dt = 0.0f;  // the rest pose
      frame.transform.rotation[3] = 1.0;
      frame.transform.translation[0] = i == 0 ? -0.2 : 0.2;
      REQUIRE(tressvk_set_frame(heads[i], &frame) == TVK_SUCCESS);
    }
    TvkSimulateInfo si{};
    si.struct_size = sizeof(si);
    si.instance_count = 2;
    si.instances = heads;
    REQUIRE(tressvk_cmd_simulate(ctx.get(), cmd, &si) == TVK_SUCCESS);
    tressvk::engine::cmd_begin_rendering(cmd, target, {});
    for (int i = 0; i < 2; ++i) {
      TvkDrawInfo di{};
      di.struct_size = sizeof(di);
      di.instance = heads[i];
      di.view = &view;
      di.materials = &materials[i];
      di.material_count = 1;
      di.light_count = 1;
      di.lights = &light;
      REQUIRE(tressvk_cmd_draw_hair(renderer, cmd, &di) == TVK_SUCCESS);
    }
    tressvk::engine::cmd_end_rendering(cmd);
  });
  const auto pixels = tressvk::engine::read_image(dev, target.color, tressvk::engine::state::kColorAttachment);
  uint32_t red_left = 0, blue_left = 0, red_right = 0, blue_right = 0;
  // Each head spans 0.25 m either side of its centre (sphere 0.1 m + strands 0.15 m), so they meet in the middle
  // third; the outer thirds belong to one head each.
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      if (x >= kW / 3 && x < 2 * kW / 3) continue;
      const auto c = pixels.rgba8(x, y);
      const bool red = c[0] > c[2] + 20, blue = c[2] > c[0] + 20;
      (x < kW / 3 ? red_left : red_right) += red ? 1u : 0u;
      (x < kW / 3 ? blue_left : blue_right) += blue ? 1u : 0u;
    }
  INFO("red left " << red_left << ", blue left " << blue_left << ", red right " << red_right << ", blue right "
                   << blue_right);
  CHECK(red_left > 100);
  CHECK(blue_right > 100);
  CHECK(blue_left == 0);
  CHECK(red_right == 0);
  CHECK(tressvk_get_last_drawn_strands(renderer) == 200);

  vkDeviceWaitIdle(dev.device());
  tressvk_destroy_renderer(renderer);
  for (TvkInstance h : heads) tressvk_destroy_instance(h);
  tressvk_destroy_asset(asset);
}

TEST_CASE("render API: a draw takes no more strands than the simulation wrote follow hairs for", "[render][vulkan]") {
  // tressvk_get_draw_strands says what a draw's LOD takes; tressvk_set_draw_strands limits the follow hairs the
  // simulation writes, and a draw never takes strands whose follows the last frame that ran did not write.
  auto& dev = tressvk::test::device();
  auto ctx = tressvk::test::create_plugin_context();
  tressvk::baker::BuiltinGroomOptions groom_options;
  groom_options.guide_count = 60;
  groom_options.follow_per_guide = 2;
  groom_options.vertices_per_strand = 8;
  TvkAsset asset = load_builtin(ctx.get(), "straight", groom_options);
  TvkInstance inst = nullptr;
  TvkInstanceCreateInfo ic{};
  ic.struct_size = sizeof(ic);
  ic.asset = asset;
  REQUIRE(tressvk_create_instance(ctx.get(), &ic, &inst) == TVK_SUCCESS);
  TvkRenderer renderer = create_rgba8_renderer(ctx.get());
  constexpr uint32_t kW = 64, kH = 64;
  const auto target = tressvk::engine::create_offscreen_target(dev, kW, kH, VK_FORMAT_R8G8B8A8_UNORM);
  TvkView view{};
  const double vp[16] = {2.5, 0, 0, 0, 0, -2.5, 0, 0, 0, 0, -0.5, 0, 0, 0, 0.5, 1};
  std::copy(std::begin(vp), std::end(vp), view.view_projection);
  view.eye[2] = 1.0;  // 1 m from the instance's origin
  view.orthographic = 1;
  view.direction[2] = -1.0f;
  view.width = kW;
  view.height = kH;
  TvkDrawInfo di{};
  di.struct_size = sizeof(di);
  di.instance = inst;
  di.view = &view;

  uint32_t strands = 0;
  CHECK(tressvk_get_draw_strands(renderer, nullptr, &strands) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(std::string(tressvk_last_error(ctx.get())).find("tressvk_get_draw_strands") != std::string::npos);
  REQUIRE(tressvk_get_draw_strands(renderer, &di, &strands) == TVK_SUCCESS);
  CHECK(strands == 180);  // LOD off: every rendered strand
  di.lod.start_distance = 0.5f;  // by distance: at 1 m, halfway to 1.5 m, 1 - 0.5 * 0.75 of the strands
  di.lod.end_distance = 1.5f;
  di.lod.min_fraction = 0.25f;
  REQUIRE(tressvk_get_draw_strands(renderer, &di, &strands) == TVK_SUCCESS);
  CHECK(strands == 113);  // ceil(0.625 * 180)

  const auto frame_with = [&](uint32_t draw_strands) {
    REQUIRE(tressvk_set_draw_strands(inst, draw_strands) == TVK_SUCCESS);
    tressvk::test::run_commands([&](VkCommandBuffer cmd) {
      REQUIRE(tressvk_new_frame(ctx.get()) == TVK_SUCCESS);
      TvkSimFrame frame{};
      frame.dt = 1.0f / 60.0f;
      frame.transform.rotation[3] = 1.0;
      REQUIRE(tressvk_set_frame(inst, &frame) == TVK_SUCCESS);
      TvkSimulateInfo si{};
      si.struct_size = sizeof(si);
      si.instance_count = 1;
      si.instances = &inst;
      REQUIRE(tressvk_cmd_simulate(ctx.get(), cmd, &si) == TVK_SUCCESS);
      tressvk::engine::cmd_begin_rendering(cmd, target, {});
      REQUIRE(tressvk_cmd_draw_hair(renderer, cmd, &di) == TVK_SUCCESS);
      tressvk::engine::cmd_end_rendering(cmd);
    });
    return tressvk_get_last_drawn_strands(renderer);
  };
  CHECK(frame_with(60) == 60);  // the guides' follows not written: the LOD's 113 would draw stale ones
  // Distances are from the instance's simulation origin, which its first frame placed at the groom: the LOD's count
  // once simulated.
  REQUIRE(tressvk_get_draw_strands(renderer, &di, &strands) == TVK_SUCCESS);
  CHECK(strands > 60);
  CHECK(frame_with(strands) == strands);  // what the LOD takes, all of it written
  di.lod = TvkLodSettings{};
  CHECK(frame_with(0) == 180);    // every strand

  vkDeviceWaitIdle(dev.device());
  tressvk_destroy_renderer(renderer);
  tressvk_destroy_instance(inst);
  tressvk_destroy_asset(asset);
}
