// The rendering C interface refuses bad input with TVK_ERROR_INVALID_ARGUMENT and a message naming what was
// wrong (no exception crosses it), and creates and destroys a renderer cleanly under validation.
#include <tressvk/test/vulkan.hpp>

#include <catch2/catch_test_macros.hpp>

#include <string>

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
