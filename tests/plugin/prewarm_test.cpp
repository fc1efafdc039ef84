// tressvk_prewarm_instance / tressvk_prewarm_renderer: the pipelines are built ahead of the first frame, so the
// first simulate and draw build none. Pipeline and shader-module creation are fallible Vulkan calls, which the
// fault-injection hook (plugin/src/core/fault_injection.hpp) counts: the warm first frame makes fewer of them than
// the cold one, and a second prewarm makes none.
#include "sim_harness.hpp"

#include "fault_context.hpp"

#include <tressvk/engine/image.hpp>

#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <iterator>

using namespace tressvk;

namespace {

struct Counts {
  uint64_t prewarm = 0;
  uint64_t prewarm_again = 0;
  uint64_t simulate = 0;
  uint64_t draw = 0;
};

Counts first_frame(bool prewarm, const engine::OffscreenTarget& target) {
  auto& dev = test::device();
  fault::Control control;
  fault::ChainLink link;
  TvkContext ctx = test::create_fault_injecting_context(control, link, 2, false);
  TvkAsset asset = test::load_asset(ctx, test::small_groom("straight", 12, 1));
  TvkInstanceCreateInfo ci{};
  ci.struct_size = sizeof(ci);
  ci.asset = asset;
  TvkInstance instance = nullptr;
  REQUIRE(tressvk_create_instance(ctx, &ci, &instance) == TVK_SUCCESS);
  TvkRendererCreateInfo ri{};
  ri.struct_size = sizeof(ri);
  ri.shading.color_format = VK_FORMAT_R8G8B8A8_UNORM;
  ri.shading.depth_format = VK_FORMAT_D32_SFLOAT;
  TvkRenderer renderer = nullptr;
  REQUIRE(tressvk_create_renderer(ctx, &ri, &renderer) == TVK_SUCCESS);
  TvkSimFrame frame = TVK_SIM_FRAME_DEFAULT_INIT;
  frame.dt = 1.0f / 60.0f;

  Counts out;
  if (prewarm) {
    control.arm(0);
    REQUIRE(tressvk_prewarm_instance(instance, &frame) == TVK_SUCCESS);
    REQUIRE(tressvk_prewarm_renderer(renderer) == TVK_SUCCESS);
    out.prewarm = control.calls;
    control.arm(0);
    REQUIRE(tressvk_prewarm_instance(instance, &frame) == TVK_SUCCESS);
    REQUIRE(tressvk_prewarm_renderer(renderer) == TVK_SUCCESS);
    out.prewarm_again = control.calls;
  }
  control.arm(0);
  REQUIRE(tressvk_set_frame(instance, &frame) == TVK_SUCCESS);
  REQUIRE(tressvk_new_frame(ctx) == TVK_SUCCESS);
  TvkResult r = TVK_SUCCESS;
  test::run_commands([&](VkCommandBuffer cmd) { r = host::record_simulate(ctx, cmd, instance); });
  REQUIRE(r == TVK_SUCCESS);
  out.simulate = control.calls;

  control.arm(0);
  const TvkView view = test::small_ortho_view();
  test::run_commands([&](VkCommandBuffer cmd) {
    engine::cmd_begin_rendering(cmd, target, {});
    TvkDrawInfo di{};
    di.struct_size = sizeof(di);
    di.instance = instance;
    di.view = &view;
    r = tressvk_cmd_draw_hair(renderer, cmd, &di);
    engine::cmd_end_rendering(cmd);
  });
  REQUIRE(r == TVK_SUCCESS);
  out.draw = control.calls;

  dev.wait_idle();
  tressvk_destroy_renderer(renderer);
  tressvk_destroy_instance(instance);
  tressvk_destroy_asset(asset);
  tressvk_destroy_context(ctx);
  return out;
}

}  // namespace

TEST_CASE("prewarm builds the pipelines of the first simulate and draw ahead of time", "[plugin][prewarm]") {
  const auto target = engine::create_offscreen_target(test::device(), 32, 32, VK_FORMAT_R8G8B8A8_UNORM);
  const Counts cold = first_frame(false, target);
  const Counts warm = first_frame(true, target);
  INFO("fallible Vulkan calls, cold: simulate " << cold.simulate << ", draw " << cold.draw << "; warm: prewarm "
                                                << warm.prewarm << ", simulate " << warm.simulate << ", draw "
                                                << warm.draw);
  CHECK(warm.prewarm > 0);
  CHECK(warm.prewarm_again == 0);  // nothing is built twice
  CHECK(warm.simulate < cold.simulate);
  CHECK(warm.draw < cold.draw);
}

TEST_CASE("prewarm refuses NULL and a bad frame with a message", "[plugin][prewarm]") {
  CHECK(tressvk_prewarm_instance(nullptr, nullptr) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(tressvk_prewarm_renderer(nullptr) == TVK_ERROR_INVALID_ARGUMENT);
  test::PluginContext ctx = test::create_plugin_context();
  TvkAsset asset = test::load_asset(ctx.get(), test::small_groom("straight", 4));
  TvkInstanceCreateInfo ci{};
  ci.struct_size = sizeof(ci);
  ci.asset = asset;
  TvkInstance instance = nullptr;
  REQUIRE(tressvk_create_instance(ctx.get(), &ci, &instance) == TVK_SUCCESS);
  TvkSimFrame zeroed{};  // a zero rotation quaternion
  CHECK(tressvk_prewarm_instance(instance, &zeroed) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(std::string(tressvk_last_error(ctx.get())).find("tressvk_prewarm_instance") != std::string::npos);
  tressvk_destroy_instance(instance);
  tressvk_destroy_asset(asset);
}
