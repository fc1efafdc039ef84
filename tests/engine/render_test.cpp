#include <tressvk/engine/image.hpp>
#include <tressvk/engine/pipeline.hpp>
#include <tressvk/engine/png.hpp>
#include <tressvk/engine/shaders.hpp>
#include <tressvk/test/vulkan.hpp>

#include <catch2/catch_test_macros.hpp>
#include <catch2/generators/catch_generators.hpp>

#include <array>
#include <cstdlib>

using namespace tressvk;

namespace {

using Rgba = std::array<uint8_t, 4>;

engine::shaders::TrianglePush flat_triangle(const float (&xy)[3][2], float z, const float (&color)[4]) {
  engine::shaders::TrianglePush push{};
  for (int v = 0; v < 3; ++v) {
    push.position[v][0] = xy[v][0];
    push.position[v][1] = xy[v][1];
    push.position[v][2] = z;
    push.position[v][3] = 1.0f;
    for (int c = 0; c < 4; ++c) push.color[v][c] = color[c];
  }
  return push;
}

// Pixel centre of the pixel containing NDC point (x, y) on a square target of `size` pixels.
std::array<uint32_t, 2> pixel_at(float x, float y, uint32_t size) {
  return {static_cast<uint32_t>((x + 1.0f) * 0.5f * static_cast<float>(size)),
          static_cast<uint32_t>((y + 1.0f) * 0.5f * static_cast<float>(size))};
}

}  // namespace

TEST_CASE("offscreen clear + depth-tested draws read back the expected pixels", "[vulkan][engine]") {
  // Both ways a host renders: dynamic rendering and a classic render pass (the plugin must draw into both).
  const bool use_render_pass = GENERATE(false, true);
  INFO((use_render_pass ? "VkRenderPass" : "dynamic rendering"));
  constexpr uint32_t kSize = 64;
  constexpr VkFormat kColor = VK_FORMAT_R8G8B8A8_UNORM;  // UNORM: clear values map to bytes exactly
  engine::Device& dev = test::device();
  engine::OffscreenTarget target = engine::create_offscreen_target(dev, kSize, kSize, kColor);
  engine::RenderPassTarget pass;
  if (use_render_pass) pass = engine::RenderPassTarget(dev, target);

  engine::GraphicsPipelineDesc desc;
  desc.vertex_spirv = engine::shaders::triangle_vert();
  desc.fragment_spirv = engine::shaders::triangle_frag();
  desc.layout.push_constant_size = sizeof(engine::shaders::TrianglePush);
  desc.color_formats = {kColor};
  desc.depth_format = VK_FORMAT_D32_SFLOAT;
  desc.depth_compare = VK_COMPARE_OP_LESS;
  desc.render_pass = pass.render_pass();
  const engine::Pipeline pipeline = engine::create_graphics_pipeline(dev, desc);

  // Green in front (z 0.25), drawn first; red behind (z 0.75), drawn second and overlapping the green one
  // on the left. Where they overlap, the depth test must keep green. Colours 0/1 map to bytes exactly.
  const float green_xy[3][2] = {{-0.5f, -0.5f}, {0.5f, -0.5f}, {0.0f, 0.5f}};
  const float red_xy[3][2] = {{-0.9f, -0.9f}, {0.0f, -0.9f}, {-0.9f, 0.9f}};
  const float green[4] = {0.0f, 1.0f, 0.0f, 1.0f};
  const float red[4] = {1.0f, 0.0f, 0.0f, 1.0f};
  engine::ClearValues clear;
  clear.color = {0.2f, 0.4f, 0.6f, 1.0f};

  test::run_commands([&](VkCommandBuffer cmd) {
    if (use_render_pass)
      engine::cmd_begin_render_pass(cmd, pass, clear);
    else
      engine::cmd_begin_rendering(cmd, target, clear);
    pipeline.cmd_bind(cmd);
    pipeline.cmd_push(cmd, flat_triangle(green_xy, 0.25f, green));
    vkCmdDraw(cmd, 3, 1, 0, 0);
    pipeline.cmd_push(cmd, flat_triangle(red_xy, 0.75f, red));
    vkCmdDraw(cmd, 3, 1, 0, 0);
    if (use_render_pass)
      engine::cmd_end_render_pass(cmd);
    else
      engine::cmd_end_rendering(cmd);
  });
  const engine::Pixels pixels = engine::read_image(dev, target.color, engine::state::kColorAttachment);
  engine::write_png(test::output_dir() / (use_render_pass ? "engine_clear_draw_render_pass.png"
                                                          : "engine_clear_draw_dynamic.png"),
                    pixels);

  const Rgba kClear{51, 102, 153, 255};  // round(0.2*255), round(0.4*255), round(0.6*255)
  const Rgba kGreen{0, 255, 0, 255};
  const Rgba kRed{255, 0, 0, 255};
  REQUIRE(pixels.width == kSize);
  REQUIRE(pixels.height == kSize);

  auto at = [&](float x, float y) {
    const auto p = pixel_at(x, y, kSize);
    return pixels.rgba8(p[0], p[1]);
  };
  CHECK(at(0.0f, 0.0f) == kGreen);     // centre: green only
  CHECK(at(-0.3f, -0.4f) == kGreen);   // overlap: green is nearer
  CHECK(at(-0.8f, 0.0f) == kRed);      // red only
  CHECK(at(0.8f, 0.8f) == kClear);     // nothing drawn
  CHECK(pixels.rgba8(0, kSize - 1) == kClear);
  CHECK(pixels.rgba8(kSize - 1, 0) == kClear);

  // Every pixel is exactly one of the three colours (flat colours, no blending, one sample).
  size_t green_count = 0;
  size_t other = 0;
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x < kSize; ++x) {
      const Rgba p = pixels.rgba8(x, y);
      if (p == kGreen) ++green_count;
      else if (p != kRed && p != kClear) ++other;
    }
  CHECK(other == 0);
  // The green triangle covers 0.5 * 32 * 32 = 512 pixel areas. Rasterisation decides edge pixels by their
  // centres, so the count may differ by up to about half the perimeter in pixels (32 + 2 * 35.8 ≈ 104 / 2);
  // the part hidden by nothing (red is behind) does not change it.
  CHECK(std::abs(static_cast<long>(green_count) - 512) <= 52);

  // Depth reads back as the nearest surface's z (shadow-map tests rely on this): the exact vertex z where one
  // triangle covers (constant z, so no interpolation error), the clear value where none does.
  const engine::Pixels depth = engine::read_image(
      dev, target.depth, use_render_pass ? engine::state::kDepthStencilAttachment : engine::state::kDepthAttachment);
  auto depth_at = [&](float x, float y) {
    const auto p = pixel_at(x, y, kSize);
    return depth.r32f(p[0], p[1]);
  };
  CHECK(depth_at(0.0f, 0.0f) == 0.25f);
  CHECK(depth_at(-0.3f, -0.4f) == 0.25f);
  CHECK(depth_at(-0.8f, 0.0f) == 0.75f);
  CHECK(depth_at(0.8f, 0.8f) == 1.0f);
}
