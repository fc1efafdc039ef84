// The error model of the C interface: every failing call returns a TvkResult and records a message naming the
// call and the field at fault (tressvk_last_error), and leaves nothing behind -- no object, no GPU memory, no
// asset pinned by a half-made instance -- so the host can fix the input and call again. Also the host contract
// under misuse (objects of another context, an asset destroyed while instances use it, wrong struct_size).
// Leaks of host memory are caught by running these tests under ASan as well (the sanitize preset).
#include "leak_check.hpp"
#include "sim_harness.hpp"

#include <tressvk/asset_io.hpp>

#include <catch2/catch_test_macros.hpp>

#include <limits>
#include <string>

using namespace tressvk;

namespace {

uint32_t allocations(TvkContext ctx) {
  TvkMemoryUsage usage{};
  REQUIRE(tressvk_get_memory_usage(ctx, &usage) == TVK_SUCCESS);
  return usage.allocation_count;
}

// Retires every deferred release (the fixture waited for all submitted work).
void retire(TvkContext ctx) {
  for (int i = 0; i < 4; ++i) REQUIRE(tressvk_new_frame(ctx) == TVK_SUCCESS);
}

// Everything the test made is gone: the deferred releases retired leave no allocation, and after the context's
// destruction no host allocation is left either.
void release_all(test::PluginContext ctx) {
  retire(ctx.get());
  CHECK(allocations(ctx.get()) == 0);
  ctx.reset();
  test::check_no_host_leaks();
}

bool mentions(const char* message, const std::string& what) {
  INFO("message: " << message);
  return std::string(message).find(what) != std::string::npos;
}

TvkResult try_create_instance(TvkContext ctx, TvkAsset asset, const TvkSimSettings* settings,
                              const TvkSimParams* params, TvkInstance* out, size_t struct_size = 0) {
  TvkInstanceCreateInfo ci{};
  ci.struct_size = struct_size ? struct_size : sizeof(ci);
  ci.asset = asset;
  ci.settings = settings;
  ci.params = params;
  return tressvk_create_instance(ctx, &ci, out);
}

}  // namespace

TEST_CASE("tressvk_create_context refuses bad settings naming the field, with the thread's last error",
          "[plugin][errors]") {
  const TvkContextCreateInfo good = host::context_info(test::device());
  struct Case {
    const char* field;
    TvkResult expected;
    void (*spoil)(TvkContextCreateInfo&);
  };
  const Case cases[] = {
      {"struct_size", TVK_ERROR_INVALID_ARGUMENT, [](TvkContextCreateInfo& i) { i.struct_size -= 8; }},
      {"instance", TVK_ERROR_INVALID_ARGUMENT, [](TvkContextCreateInfo& i) { i.instance = VK_NULL_HANDLE; }},
      {"physical_device", TVK_ERROR_INVALID_ARGUMENT,
       [](TvkContextCreateInfo& i) { i.physical_device = VK_NULL_HANDLE; }},
      {"device", TVK_ERROR_INVALID_ARGUMENT, [](TvkContextCreateInfo& i) { i.device = VK_NULL_HANDLE; }},
      {"get_instance_proc_addr", TVK_ERROR_INVALID_ARGUMENT,
       [](TvkContextCreateInfo& i) { i.get_instance_proc_addr = nullptr; }},
      {"frames_in_flight", TVK_ERROR_INVALID_ARGUMENT, [](TvkContextCreateInfo& i) { i.frames_in_flight = 1000; }},
      {"api_version", TVK_ERROR_MISSING_FEATURE, [](TvkContextCreateInfo& i) { i.api_version = VK_API_VERSION_1_1; }},
  };
  for (const Case& c : cases) {
    INFO("field " << c.field);
    TvkContextCreateInfo info = good;
    c.spoil(info);
    TvkContext ctx = reinterpret_cast<TvkContext>(0x1);
    CHECK(tressvk_create_context(&info, &ctx) == c.expected);
    CHECK(ctx == nullptr);
    CHECK(mentions(tressvk_last_error(nullptr), "tressvk_create_context"));
    CHECK(mentions(tressvk_last_error(nullptr), c.field));
  }
  CHECK(tressvk_create_context(nullptr, nullptr) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(mentions(tressvk_last_error(nullptr), "out_context"));
  // The host fixes the input and calls again.
  TvkContextCreateInfo info = good;
  TvkContext ctx = nullptr;
  REQUIRE(tressvk_create_context(&info, &ctx) == TVK_SUCCESS);
  tressvk_destroy_context(ctx);
  test::check_no_host_leaks();
}

TEST_CASE("tressvk_create_instance with bad settings leaks nothing and does not pin the asset", "[plugin][errors]") {
  test::PluginContext ctx = test::create_plugin_context();
  TvkAsset a = test::load_asset(ctx.get(), test::small_groom("straight", 8));
  retire(ctx.get());  // the upload's staging buffer goes
  const uint32_t with_asset = allocations(ctx.get());

  struct Case {
    const char* field;
    void (*spoil)(TvkSimSettings&, TvkSimParams&);
  };
  const Case cases[] = {
      {"time.step_rate", [](TvkSimSettings& s, TvkSimParams&) { s.time.step_rate = 10.0f; }},
      {"time.step_rate", [](TvkSimSettings& s, TvkSimParams&) { s.time.step_rate = 1000.0f; }},
      {"time.max_steps_per_frame", [](TvkSimSettings& s, TvkSimParams&) { s.time.max_steps_per_frame = 0; }},
      {"time.max_steps_per_frame",
       [](TvkSimSettings& s, TvkSimParams&) { s.time.max_steps_per_frame = TVK_MAX_STEPS_PER_FRAME + 1; }},
      {"time.max_steps_sustained",
       [](TvkSimSettings& s, TvkSimParams&) { s.time.max_steps_sustained = TVK_MAX_STEPS_PER_FRAME + 1; }},
      {"gravity", [](TvkSimSettings& s, TvkSimParams&) { s.gravity[1] = std::numeric_limits<float>::infinity(); }},
      {"model", [](TvkSimSettings& s, TvkSimParams&) { s.model = static_cast<TvkSimModel>(7); }},
      {"local_stiffness", [](TvkSimSettings&, TvkSimParams& p) { p.local_stiffness = 2.0f; }},
  };
  for (const Case& c : cases) {
    INFO("field " << c.field);
    TvkSimSettings settings = TVK_SIM_SETTINGS_DEFAULT_INIT;
    TvkSimParams params = TVK_SIM_PARAMS_DEFAULT_INIT;
    c.spoil(settings, params);
    TvkInstance inst = reinterpret_cast<TvkInstance>(0x1);
    CHECK(try_create_instance(ctx.get(), a, &settings, &params, &inst) == TVK_ERROR_INVALID_ARGUMENT);
    CHECK(inst == nullptr);
    CHECK(mentions(tressvk_last_error(ctx.get()), "tressvk_create_instance"));
    CHECK(mentions(tressvk_last_error(ctx.get()), c.field));
    retire(ctx.get());
    CHECK(allocations(ctx.get()) == with_asset);
  }
  TvkInstance inst = nullptr;
  CHECK(try_create_instance(ctx.get(), a, nullptr, nullptr, &inst, sizeof(TvkInstanceCreateInfo) + 4) ==
        TVK_ERROR_INVALID_ARGUMENT);
  CHECK(mentions(tressvk_last_error(ctx.get()), "struct_size"));
  CHECK(try_create_instance(ctx.get(), nullptr, nullptr, nullptr, &inst) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(mentions(tressvk_last_error(ctx.get()), "asset"));
  // The failed calls did not count as users: destroying the host's handle frees the asset.
  tressvk_destroy_asset(a);
  release_all(std::move(ctx));
}

TEST_CASE("tressvk_load_asset failures name the field and leave nothing behind", "[plugin][errors]") {
  test::PluginContext ctx = test::create_plugin_context();
  const std::vector<std::byte> bytes = asset::write(test::small_groom("straight", 8));
  const auto load = [&](TvkAssetLoadInfo info, TvkAsset* out) {
    TvkResult r = TVK_SUCCESS;
    test::run_commands([&](VkCommandBuffer cmd) {
      if (info.upload_command_buffer) info.upload_command_buffer = cmd;
      r = tressvk_load_asset(ctx.get(), &info, out);
    });
    return r;
  };
  TvkAssetLoadInfo good{};
  good.struct_size = sizeof(good);
  good.data = bytes.data();
  good.size = bytes.size();
  good.upload_command_buffer = reinterpret_cast<VkCommandBuffer>(0x1);  // replaced by the recording one
  TvkAsset a = reinterpret_cast<TvkAsset>(0x1);
  TvkAssetLoadInfo info = good;
  info.struct_size = 8;
  CHECK(load(info, &a) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(a == nullptr);
  CHECK(mentions(tressvk_last_error(ctx.get()), "struct_size"));
  info = good;
  info.upload_command_buffer = VK_NULL_HANDLE;
  CHECK(load(info, &a) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(mentions(tressvk_last_error(ctx.get()), "upload_command_buffer"));
  info = good;
  info.size = 0;
  CHECK(load(info, &a) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(mentions(tressvk_last_error(ctx.get()), "data"));
  info = good;
  info.size = bytes.size() - 1;
  CHECK(load(info, &a) == TVK_ERROR_INVALID_ASSET);
  CHECK(mentions(tressvk_last_error(ctx.get()), "<memory>"));
  CHECK(tressvk_load_asset(nullptr, &good, &a) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(mentions(tressvk_last_error(nullptr), "tressvk_load_asset"));
  retire(ctx.get());
  CHECK(allocations(ctx.get()) == 0);
  // And the same call with the input fixed succeeds.
  REQUIRE(load(good, &a) == TVK_SUCCESS);
  tressvk_destroy_asset(a);
  release_all(std::move(ctx));
}

TEST_CASE("host misuse gets a clear error: objects of another context, wrong struct_size", "[plugin][errors]") {
  test::PluginContext ctx = test::create_plugin_context();
  test::PluginContext other = test::create_plugin_context();
  TvkAsset a = test::load_asset(ctx.get(), test::small_groom("straight", 8));
  TvkInstance inst = nullptr;
  // An asset of another context.
  CHECK(try_create_instance(other.get(), a, nullptr, nullptr, &inst) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(mentions(tressvk_last_error(other.get()), "another context"));
  REQUIRE(try_create_instance(ctx.get(), a, nullptr, nullptr, &inst) == TVK_SUCCESS);
  // An instance of another context.
  TvkResult r = TVK_SUCCESS;
  test::run_commands([&](VkCommandBuffer cmd) { r = host::record_simulate(other.get(), cmd, inst); });
  CHECK(r == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(mentions(tressvk_last_error(other.get()), "another context"));
  // Wrong struct_size.
  test::run_commands([&](VkCommandBuffer cmd) {
    TvkSimulateInfo si{};
    si.struct_size = sizeof(si) - 4;
    si.instance_count = 1;
    si.instances = &inst;
    r = tressvk_cmd_simulate(ctx.get(), cmd, &si);
  });
  CHECK(r == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(mentions(tressvk_last_error(ctx.get()), "struct_size"));
  // NULL handles and outputs.
  CHECK(tressvk_set_sim_settings(inst, nullptr) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(mentions(tressvk_last_error(ctx.get()), "settings"));
  CHECK(tressvk_get_instance_stats(nullptr, nullptr) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(mentions(tressvk_last_error(nullptr), "tressvk_get_instance_stats"));
  // A refused settings change keeps the old settings and the instance keeps working.
  TvkSimSettings bad = TVK_SIM_SETTINGS_DEFAULT_INIT;
  bad.time.step_rate = 5.0f;
  CHECK(tressvk_set_sim_settings(inst, &bad) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(mentions(tressvk_last_error(ctx.get()), "time.step_rate"));
  tressvk_destroy_instance(inst);
  tressvk_destroy_asset(a);
  retire(ctx.get());
  CHECK(allocations(ctx.get()) == 0);
  ctx.reset();
  other.reset();
  test::check_no_host_leaks();
}

TEST_CASE("an asset destroyed while an instance uses it lives on until the instance goes", "[plugin][errors]") {
  test::PluginContext ctx = test::create_plugin_context();
  TvkAsset a = test::load_asset(ctx.get(), test::small_groom("straight", 8));
  {
    test::GpuInstance inst(ctx.get(), a, {}, TvkSimSettings TVK_SIM_SETTINGS_DEFAULT_INIT);
    tressvk_destroy_asset(a);  // the host's handle is gone; the instance still holds the asset
    TvkSimFrame frame{};
    frame.dt = 1.0f / 60.0f;
    frame.transform.rotation[3] = 1.0;
    frame.wind = TvkWind TVK_WIND_DEFAULT_INIT;
    for (int i = 0; i < 3; ++i) inst.run_frame(frame);  // no validation message: the static buffers are alive
    CHECK(inst.stats().frames == 3);
    retire(ctx.get());
    CHECK(allocations(ctx.get()) > 0);
  }
  release_all(std::move(ctx));
}
