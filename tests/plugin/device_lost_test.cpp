// Device loss and drawing before simulating: the host contract under the two misuses a renderer meets in the field.
//
// A lost device cannot be produced on lavapipe, so the tests play both ways it reaches TressVK: the host's own
// vkQueueSubmit returning VK_ERROR_DEVICE_LOST (the host calls tressvk_report_device_lost), and one of the plugin's
// own calls returning it (the fault-injection link makes vkGetQueryPoolResults report a lost device, as a real
// driver does once the device is gone). Either way every call that would use the device must refuse with
// TVK_ERROR_DEVICE_LOST and a message, destruction must release everything without waiting for the GPU, and a new
// context must give the same simulation as before the loss (a host recreates its VkDevice; here the fixture's
// device stands in for the new one).
#include "leak_check.hpp"
#include "sim_harness.hpp"

#include "fault_context.hpp"

#include <tressvk/asset_io.hpp>
#include <tressvk/host/plugin_host.hpp>
#include <tressvk/engine/image.hpp>

#include <catch2/catch_test_macros.hpp>

#include <string>
#include <vector>

using namespace tressvk;

namespace {

bool says(TvkContext ctx, const char* what) { return std::string(tressvk_last_error(ctx)).find(what) != std::string::npos; }

TvkSimFrame moving_frame(int i) {
  TvkSimFrame f = TVK_SIM_FRAME_DEFAULT_INIT;
  f.dt = 1.0f / 60.0f;
  f.transform.translation[0] = 0.02 * i;  // the head moves, so the state depends on every frame
  return f;
}

TvkRendererCreateInfo renderer_info() {
  TvkRendererCreateInfo ri{};
  ri.struct_size = sizeof(ri);
  ri.shading.color_format = VK_FORMAT_R8G8B8A8_UNORM;
  ri.shading.depth_format = VK_FORMAT_D32_SFLOAT;
  return ri;
}

// Simulates `frames` frames of a fresh context on the fixture's device and returns the positions read back.
std::vector<test::Point> simulate_fresh(const asset::HairAsset& groom, int frames) {
  auto& dev = test::device();
  TvkContextCreateInfo info = host::context_info(dev);
  TvkContext ctx = nullptr;
  REQUIRE(tressvk_create_context(&info, &ctx) == TVK_SUCCESS);
  std::vector<test::Point> out;
  {
    TvkAsset asset = test::load_asset(ctx, groom);
    test::GpuInstance inst(ctx, asset, {}, TVK_SIM_SETTINGS_DEFAULT_INIT);
    for (int i = 0; i < frames; ++i) inst.run_frame(moving_frame(i));
    out = inst.state().pos;
    tressvk_destroy_asset(asset);
  }
  dev.wait_idle();
  for (int i = 0; i < 3; ++i) tressvk_new_frame(ctx);
  tressvk_destroy_context(ctx);
  return out;
}

}  // namespace

TEST_CASE("a device lost in the host's submit: every device call refuses, teardown frees all, a new context recovers",
          "[plugin][faults][device_lost]") {
  auto& dev = test::device();
  const asset::HairAsset groom = test::small_groom("straight", 16, 1);
  const std::vector<test::Point> expected = simulate_fresh(groom, 3);

  TvkContextCreateInfo info = host::context_info(dev);
  TvkContext ctx = nullptr;
  REQUIRE(tressvk_create_context(&info, &ctx) == TVK_SUCCESS);
  TvkAsset asset = test::load_asset(ctx, groom);
  TvkInstance instance = nullptr;
  TvkInstanceCreateInfo ci{};
  ci.struct_size = sizeof(ci);
  ci.asset = asset;
  REQUIRE(tressvk_create_instance(ctx, &ci, &instance) == TVK_SUCCESS);
  const TvkRendererCreateInfo ri = renderer_info();
  TvkRenderer renderer = nullptr;
  REQUIRE(tressvk_create_renderer(ctx, &ri, &renderer) == TVK_SUCCESS);
  const auto simulate = [&](int i) {
    const TvkSimFrame f = moving_frame(i);
    REQUIRE(tressvk_set_frame(instance, &f) == TVK_SUCCESS);
    TvkResult r = tressvk_new_frame(ctx);
    if (r != TVK_SUCCESS) return r;
    test::run_commands([&](VkCommandBuffer cmd) { r = host::record_simulate(ctx, cmd, instance); });
    return r;
  };
  REQUIRE(simulate(0) == TVK_SUCCESS);
  REQUIRE(simulate(1) == TVK_SUCCESS);
  CHECK(tressvk_is_device_lost(ctx) == VK_FALSE);

  // The host's submit of the next frame returned VK_ERROR_DEVICE_LOST.
  tressvk_report_device_lost(ctx);
  CHECK(tressvk_is_device_lost(ctx) == VK_TRUE);
  CHECK(simulate(2) == TVK_ERROR_DEVICE_LOST);
  CHECK(says(ctx, "device was lost"));
  CHECK(says(ctx, "tressvk_new_frame"));
  {
    TvkResult r = TVK_SUCCESS;
    test::run_commands([&](VkCommandBuffer cmd) { r = host::record_simulate(ctx, cmd, instance); });
    CHECK(r == TVK_ERROR_DEVICE_LOST);
    CHECK(says(ctx, "tressvk_cmd_simulate"));
  }
  TvkInstance second = nullptr;
  CHECK(tressvk_create_instance(ctx, &ci, &second) == TVK_ERROR_DEVICE_LOST);
  CHECK(second == nullptr);
  TvkRenderer second_renderer = nullptr;
  CHECK(tressvk_create_renderer(ctx, &ri, &second_renderer) == TVK_ERROR_DEVICE_LOST);
  CHECK(second_renderer == nullptr);
  {
    const TvkView view = test::small_ortho_view();
    TvkDrawInfo di{};
    di.struct_size = sizeof(di);
    di.instance = instance;
    di.view = &view;
    const auto target = engine::create_offscreen_target(dev, 32, 32, VK_FORMAT_R8G8B8A8_UNORM);
    CHECK(test::draw_hair(renderer, target, di) == TVK_ERROR_DEVICE_LOST);
    CHECK(says(ctx, "tressvk_cmd_draw_hair"));
    CHECK(test::raster_hair(renderer, di) == TVK_ERROR_DEVICE_LOST);
    TvkResult r = TVK_SUCCESS;
    test::run_commands([&](VkCommandBuffer cmd) {
      engine::cmd_begin_rendering(cmd, target, {});
      r = tressvk_cmd_composite_hair(renderer, cmd);
      engine::cmd_end_rendering(cmd);
    });
    CHECK(r == TVK_ERROR_DEVICE_LOST);
  }
  // Teardown never waits for the GPU and releases everything (the new_frame of a lost context frees what was
  // deferred at once).
  dev.wait_idle();
  tressvk_destroy_renderer(renderer);
  tressvk_destroy_instance(instance);
  tressvk_destroy_asset(asset);
  CHECK(tressvk_new_frame(ctx) == TVK_ERROR_DEVICE_LOST);
  TvkMemoryUsage usage{};
  REQUIRE(tressvk_get_memory_usage(ctx, &usage) == TVK_SUCCESS);
  CHECK(usage.allocation_count == 0);
  tressvk_destroy_context(ctx);

  // Recovery: a new context (on the host's new device) simulates exactly as before the loss.
  const std::vector<test::Point> again = simulate_fresh(groom, 3);
  REQUIRE(again.size() == expected.size());
  size_t differing = 0;
  for (size_t i = 0; i < again.size(); ++i) differing += again[i] != expected[i];
  CHECK(differing == 0);
  test::check_no_host_leaks();
}

TEST_CASE("a device loss met by the plugin's own call marks the context lost", "[plugin][faults][device_lost]") {
  auto& dev = test::device();
  fault::Control control;
  fault::ChainLink link;
  TvkContext ctx = test::create_fault_injecting_context(control, link, 0, true);
  {
    TvkAsset asset = test::load_asset(ctx, test::small_groom("straight", 8));
    test::GpuInstance inst(ctx, asset, {}, TVK_SIM_SETTINGS_DEFAULT_INIT);
    for (int i = 0; i < 4; ++i) inst.run_frame(moving_frame(i));
    TvkPassTiming timings[32];
    REQUIRE(tressvk_new_frame(ctx) == TVK_SUCCESS);  // the last frame's slice is readable until it is recorded again
    REQUIRE(tressvk_get_pass_timings(ctx, timings, 32) > 0);  // the frames were timed

    control.device_lost = true;  // the driver now reports the device as lost
    CHECK(tressvk_get_pass_timings(ctx, timings, 32) == 0);
    CHECK(tressvk_is_device_lost(ctx) == VK_TRUE);
    CHECK(says(ctx, "VK_ERROR_DEVICE_LOST"));
    CHECK(says(ctx, "vkGetQueryPoolResults"));
    CHECK(tressvk_new_frame(ctx) == TVK_ERROR_DEVICE_LOST);
    TvkAsset other = nullptr;
    const std::vector<std::byte> bytes = asset::write(test::small_groom("straight", 8));
    TvkResult r = TVK_SUCCESS;
    test::run_commands([&](VkCommandBuffer cmd) { r = host::record_load_asset(ctx, cmd, bytes, &other); });
    CHECK(r == TVK_ERROR_DEVICE_LOST);
    CHECK(other == nullptr);
    tressvk_destroy_asset(asset);
  }
  dev.wait_idle();
  tressvk_new_frame(ctx);
  TvkMemoryUsage usage{};
  REQUIRE(tressvk_get_memory_usage(ctx, &usage) == TVK_SUCCESS);
  CHECK(usage.allocation_count == 0);
  tressvk_destroy_context(ctx);
  test::check_no_host_leaks();
}

TEST_CASE("drawing an instance that was never simulated is refused with a message", "[plugin][misuse]") {
  auto& dev = test::device();
  TvkContextCreateInfo info = host::context_info(dev);
  TvkContext ctx = nullptr;
  REQUIRE(tressvk_create_context(&info, &ctx) == TVK_SUCCESS);
  const auto target = engine::create_offscreen_target(dev, 32, 32, VK_FORMAT_R8G8B8A8_UNORM);
  {
    TvkAsset asset = test::load_asset(ctx, test::small_groom("straight", 8));
    test::GpuInstance inst(ctx, asset, {}, TVK_SIM_SETTINGS_DEFAULT_INIT);
    const TvkRendererCreateInfo ri = renderer_info();
    TvkRenderer renderer = nullptr;
    REQUIRE(tressvk_create_renderer(ctx, &ri, &renderer) == TVK_SUCCESS);
    const TvkView view = test::small_ortho_view();
    TvkDrawInfo di{};
    di.struct_size = sizeof(di);
    di.instance = inst.handle();
    di.view = &view;
    const auto draw = [&] { return test::draw_hair(renderer, target, di); };
    CHECK(draw() == TVK_ERROR_INVALID_ARGUMENT);
    CHECK(says(ctx, "tressvk_cmd_draw_hair"));
    CHECK(says(ctx, "not been simulated"));
    CHECK(test::raster_hair(renderer, di) == TVK_ERROR_INVALID_ARGUMENT);
    CHECK(says(ctx, "not been simulated"));

    inst.run_frame(moving_frame(0));
    CHECK(draw() == TVK_SUCCESS);
    dev.wait_idle();
    tressvk_destroy_renderer(renderer);
    tressvk_destroy_asset(asset);
  }
  dev.wait_idle();
  for (int i = 0; i < 3; ++i) tressvk_new_frame(ctx);
  tressvk_destroy_context(ctx);
}
